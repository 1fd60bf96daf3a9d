//! The lot's load test (issue 41): 8 stations at once against one throwaway PostgreSQL server, 100
//! simulated boards each, every certificate through its station's queue as `calibrate --lot
//! postgres://...` sends it (connect, migrate check, one transaction); then every certificate must be
//! in the lot exactly once. Beside it, one station's 100 boards into a SQLite file as `calibrate --lot
//! FILE` adds them. Prints the time per board of each (wall time of the upload alone: the certificates
//! are made before the clock starts). Run: `cargo run -p accelcal --release --example lot_load [STATIONS BOARDS]`.

// NOTE: the tests' throwaway server; the example uses its start and address only.
#[allow(dead_code)]
#[path = "../tests/common/throwaway_postgres.rs"]
mod throwaway_postgres;

use std::path::Path;
use std::time::{Duration, Instant};

use accelcal::certificate::Certificate;
use accelcal::lot::queue::Queue;
use accelcal::lot::Lot;

fn main() {
    let mut args = std::env::args().skip(1).map(|a| a.parse::<usize>().expect("STATIONS BOARDS: two counts"));
    let (stations, boards) = (args.next().unwrap_or(8), args.next().unwrap_or(100));
    // NOTE: one station's more: the same station alone on the server, after the others.
    let mut per_station: Vec<Vec<Certificate>> = certificates(stations + 1, boards);
    let alone = per_station.pop().unwrap_or_default();
    let dir = std::env::temp_dir().join(format!("accelcal-lot-load-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let server = throwaway_postgres::Server::start("load");
    let url = server.url();
    let started = Instant::now();
    let times: Vec<Vec<Duration>> = std::thread::scope(|scope| {
        let running: Vec<_> = per_station
            .iter()
            .enumerate()
            .map(|(s, certificates)| {
                let queue = Queue { dir: dir.join(format!("station{s}")), station: Some(format!("station-{s}")) };
                let url = &url;
                scope.spawn(move || upload_each(&queue, url, certificates))
            })
            .collect();
        running.into_iter().map(|t| t.join().unwrap()).collect()
    });
    let wall = started.elapsed();
    let expected = (stations * boards) as i64;
    let parameters = check_each_once(&url, expected);
    let alone_queue = Queue { dir: dir.join("alone"), station: Some("alone".into()) };
    let alone_times = upload_each(&alone_queue, &url, &alone);
    let file_times = add_each(&dir.join("one-station.sqlite"), &per_station[0]);
    println!("{stations} stations x {boards} boards into one PostgreSQL server: {expected} certificates, each once, {parameters} parameter rows, complete");
    println!("  all stations: {:.2} s wall, {:.1} boards/s", wall.as_secs_f64(), expected as f64 / wall.as_secs_f64());
    println!("  per board on a station (queue + upload): {}", figures(times.concat()));
    println!("one station alone x {boards} boards into the same server: per board {}", figures(alone_times));
    println!("one station x {boards} boards into a SQLite file: per board {}", figures(file_times));
    let _ = std::fs::remove_dir_all(&dir);
}

/// Every station's boards: four issued certificates, each board a copy under its own serial and
/// date, resealed (the budget's refits, seconds per certificate, are not what is measured).
fn certificates(stations: usize, boards: usize) -> Vec<Vec<Certificate>> {
    let issue = |seed| Certificate::issue(&accelcal::sim::sessions::adaptive(seed, 1.0, 2.8e-3)).unwrap();
    let made: Vec<Certificate> = (1..=4).map(issue).collect();
    let board = |station: usize, n: usize| {
        let mut certificate = made[n % made.len()].clone();
        certificate.board.serial = Some(format!("ST{station}-B{n:03}"));
        certificate.date_utc = Some(format!("2026-11-28 {:02}:{:02}", n / 60, n % 60));
        certificate.resealed()
    };
    (0..stations).map(|s| (0..boards).map(|n| board(s, n)).collect()).collect()
}

/// Asserts the lot holds `expected` certificates of as many serials, complete; its parameter rows.
fn check_each_once(url: &str, expected: i64) -> i64 {
    let lot = Lot::open_existing(Path::new(url)).unwrap();
    let consistency = lot.consistency().unwrap();
    let all = lot.all().unwrap();
    let mut serials: Vec<&str> = all.iter().filter_map(|(c, _)| c.board.serial.as_deref()).collect();
    serials.sort_unstable();
    serials.dedup();
    assert_eq!((consistency.certificates, serials.len() as i64, consistency.complete), (expected, expected, true));
    consistency.parameters
}

/// Each certificate kept and uploaded as a calibration would, timed.
fn upload_each(queue: &Queue, url: &str, certificates: &[Certificate]) -> Vec<Duration> {
    let timed = |certificate: &Certificate| {
        let started = Instant::now();
        let said = queue.keep_and_send(Path::new(url), certificate).unwrap();
        assert!(said.contains("uploaded"), "{said}");
        started.elapsed()
    };
    certificates.iter().map(timed).collect()
}

/// Each certificate added to the SQLite lot at `path` as a calibration would, timed.
fn add_each(path: &Path, certificates: &[Certificate]) -> Vec<Duration> {
    let timed = |certificate: &Certificate| {
        let started = Instant::now();
        Lot::add_issued(path, certificate).unwrap();
        started.elapsed()
    };
    certificates.iter().map(timed).collect()
}

/// Mean, median and largest of the times, in ms.
fn figures(mut times: Vec<Duration>) -> String {
    times.sort_unstable();
    let ms = |d: Duration| d.as_secs_f64() * 1e3;
    let mean = times.iter().map(|d| ms(*d)).sum::<f64>() / times.len() as f64;
    format!("mean {mean:.2} ms, median {:.2} ms, max {:.2} ms", ms(times[times.len() / 2]), ms(times[times.len() - 1]))
}
