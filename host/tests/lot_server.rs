//! The lot on a real PostgreSQL server (issue 41), each test against its own throwaway server
//! (common/throwaway_postgres.rs): the same commands as a file's lot, each certificate once by its
//! hash, a certificate altered in a file or on the server refused, and a station's queue that keeps
//! what the server did not take (server stopped, station killed mid-upload) until `lot sync` sends it.

mod common;

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Duration;

use accelcal::certificate::Certificate;
use accelcal::lot::queue::Queue;
use accelcal::lot::Lot;
use common::accelcal_within;
use common::throwaway_postgres::Server;

const LIMIT: Duration = Duration::from_secs(120);

fn fresh_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("accelcal-lot-server-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A sealed certificate of a made-up adaptive session (`seed`) as board `serial` calibrated on `date`.
fn certificate(seed: u64, serial: &str, date: &str) -> Certificate {
    let session = accelcal::sim::sessions::adaptive(seed, 1.0, 2.8e-3);
    let mut certificate = Certificate::issue(&session).unwrap();
    certificate.board.serial = Some(serial.to_owned());
    certificate.date_utc = Some(date.to_owned());
    certificate.resealed()
}

/// The certificate written as `dir/NAME.certificate.json`.
fn written(dir: &Path, name: &str, certificate: &Certificate) -> String {
    let file = dir.join(format!("{name}.certificate.json"));
    std::fs::write(&file, certificate.to_json()).unwrap();
    file.to_string_lossy().into_owned()
}

/// `accelcal ARGS`, which must succeed; its stdout.
fn accelcal_ok(args: &[&str]) -> String {
    let (output, _) = accelcal_within(args, LIMIT);
    assert!(output.status.success(), "{args:?}: {}", String::from_utf8_lossy(&output.stderr));
    String::from_utf8_lossy(&output.stdout).into_owned()
}

/// (certificates, parameter rows, complete) on the server, as the lot reads them.
fn counted(url: &str) -> (i64, i64, bool) {
    let consistency = Lot::open_existing(Path::new(url)).unwrap().consistency().unwrap();
    (consistency.certificates, consistency.parameters, consistency.complete)
}

#[test]
#[cfg_attr(not(has_postgres), ignore = "needs PostgreSQL's server (Debian's postgresql); CI=true runs it")]
fn the_server_lot_answers_the_file_lot_s_commands_and_keeps_a_certificate_uploaded_twice_once() {
    let (server, dir) = (Server::start("commands"), fresh_dir("commands"));
    let url = server.url();
    let (b1, b2, b1_again) = (
        certificate(1, "B1", "2026-11-24 10:00"),
        certificate(2, "B2", "2026-11-24 10:05"),
        certificate(3, "B1", "2026-11-25 09:00"),
    );
    let files = [written(&dir, "b1", &b1), written(&dir, "b2", &b2), written(&dir, "b1-again", &b1_again)];
    let added = accelcal_ok(&["lot", "add", &url, &files[0], &files[1], &files[2], "--station", "st-1"]);
    assert!(added.contains("3 added") && added.contains("(0 already there)"), "{added}");
    let again = accelcal_ok(&["lot", "add", &url, &files[0]]);
    assert!(again.contains("0 added") && again.contains("(1 already there)"), "{again}");
    // NOTE: 12 parameters per adaptive certificate; the one uploaded twice is one row.
    assert_eq!(counted(&url), (3, 36, true));
    let shown: serde_json::Value = serde_json::from_str(&accelcal_ok(&["lot", "show", &url, "--json"])).unwrap();
    assert_eq!(shown["boards"], 2);
    let history: Vec<Certificate> =
        serde_json::from_str(&accelcal_ok(&["lot", "board", &url, "B1", "--json"])).unwrap();
    assert_eq!(history, vec![b1, b1_again]);
    let stations: Vec<String> =
        Lot::open_existing(Path::new(&url)).unwrap().all().unwrap().into_iter().map(|(_, s)| s).collect();
    assert_eq!(stations, ["st-1"; 3]);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
#[cfg_attr(not(has_postgres), ignore = "needs PostgreSQL's server (Debian's postgresql); CI=true runs it")]
fn a_tampered_certificate_is_refused_on_the_server_path_as_on_the_file_path() {
    let (server, dir) = (Server::start("tampered"), fresh_dir("tampered"));
    let url = server.url();
    let sqlite = dir.join("lot.sqlite").to_string_lossy().into_owned();
    let good = written(&dir, "b1", &certificate(1, "B1", "2026-11-24 10:00"));
    let mut changed = certificate(2, "B2", "2026-11-24 10:05");
    changed.parameters.get_mut("o_x").unwrap().value += 1e-6;
    let tampered = written(&dir, "b2", &changed);
    for lot in [&url, &sqlite] {
        let (output, _) = accelcal_within(&["lot", "add", lot, &good, &tampered], LIMIT);
        let said = String::from_utf8_lossy(&output.stderr);
        assert!(!output.status.success() && said.contains("b2.certificate.json"), "{lot}: {said}");
    }
    accelcal_ok(&["lot", "add", &url, &good]);
    // An altered row on the server is refused by every read, as an altered file is.
    let stored: String = server.client().query_one("SELECT json FROM certificates", &[]).unwrap().get(0);
    let mut altered: serde_json::Value = serde_json::from_str(&stored).unwrap();
    let value = altered["parameters"]["o_x"]["value"].as_f64().unwrap();
    altered["parameters"]["o_x"]["value"] = (value + 1e-6).into();
    let altered = altered.to_string();
    server.client().execute("UPDATE certificates SET json = $1", &[&altered]).unwrap();
    let (output, _) = accelcal_within(&["lot", "show", &url], LIMIT);
    let said = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success() && said.contains("board B1's certificate hashes to"), "{said}");
    // A queued file whose hash no longer matches is refused by `lot sync` and set aside, the rest sent.
    let queue = dir.join("queue");
    std::fs::create_dir_all(&queue).unwrap();
    std::fs::copy(&tampered, queue.join("x.certificate.json")).unwrap();
    let (output, _) = accelcal_within(&["lot", "sync", &url, "--queue", &queue.to_string_lossy()], LIMIT);
    let said = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success() && said.contains("refused and set aside"), "{said}");
    assert!(queue.join("refused/x.certificate.json").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
#[cfg_attr(not(has_postgres), ignore = "needs PostgreSQL's server (Debian's postgresql); CI=true runs it")]
fn certificates_issued_while_the_server_is_stopped_wait_in_the_queue_and_sync_sends_each_once() {
    let (server, dir) = (Server::start("stopped"), fresh_dir("stopped"));
    let (url, queue) = (server.url(), Queue::at(&dir.join("queue")));
    let place = Path::new(&url);
    for seed in 1..=3 {
        let said = queue.keep_and_send(place, &certificate(seed, &format!("B{seed}"), "2026-11-24 10:00")).unwrap();
        assert!(said.contains("uploaded"), "{said}");
    }
    server.stop();
    for seed in 4..=6 {
        let said = queue.keep_and_send(place, &certificate(seed, &format!("B{seed}"), "2026-11-24 11:00")).unwrap();
        assert!(said.contains(&format!("({} waiting)", seed - 3)), "{said}");
    }
    // A calibration whose lot is down keeps its certificate in the queue and still succeeds.
    let session = dir.join("board7");
    let (output, _) = Command::new(env!("CARGO_BIN_EXE_accelcal"))
        .args(["calibrate", "--sim", "--chip-fit", "--yes", "--seed", "7", "--session"])
        .arg(&session)
        .args(["--lot", &url])
        .env("ACCELCAL_LOT_QUEUE", &queue.dir)
        .output()
        .map(|o| (o, ()))
        .unwrap();
    let said = String::from_utf8_lossy(&output.stdout).into_owned() + &String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success() && said.contains("(4 waiting)"), "{said}");
    server.restart();
    let synced = accelcal_ok(&["lot", "sync", &url, "--queue", &queue.dir.to_string_lossy()]);
    assert!(synced.contains("4 sent") && synced.contains("0 waiting"), "{synced}");
    // NOTE: 6 adaptive certificates of 12 parameters and a quick one of ortho9's 9.
    assert_eq!(counted(&url), (7, 81, true));
    assert_eq!((queue.waiting().unwrap().len(), std::fs::read_dir(queue.dir.join("sent")).unwrap().count()), (0, 7));
    let again = accelcal_ok(&["lot", "sync", &url, "--queue", &queue.dir.to_string_lossy()]);
    assert!(again.contains("0 sent"), "{again}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
#[cfg_attr(not(has_postgres), ignore = "needs PostgreSQL's server (Debian's postgresql); CI=true runs it")]
fn a_station_killed_inside_an_upload_leaves_no_part_of_its_board_and_the_next_sync_sends_it_once() {
    let (server, dir) = (Server::start("killed"), fresh_dir("killed"));
    let (url, queue) = (server.url(), Queue::at(&dir.join("queue")));
    accelcal_ok(&["lot", "add", &url, &written(&dir, "b1", &certificate(1, "B1", "2026-11-24 10:00"))]);
    queue.keep(&certificate(2, "B2", "2026-11-24 10:05")).unwrap();
    let mut station = Command::new(env!("CARGO_BIN_EXE_accelcal"))
        .args(["lot", "sync", &url, "--queue", &queue.dir.to_string_lossy()])
        .env("ACCELCAL_TEST_LOT_PAUSE_S", "60")
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let lines = BufReader::new(station.stderr.take().unwrap()).lines();
    assert!(lines.map_while(Result::ok).any(|l| l.contains("inside the transaction of board B2")));
    // NOTE: Child::kill sends SIGKILL: kill -9.
    station.kill().unwrap();
    station.wait().unwrap();
    // The server rolls back the dropped connection's transaction: B1 only, whole.
    assert_eq!(counted(&url), (1, 12, true));
    assert_eq!(queue.waiting().unwrap().len(), 1, "the killed station's certificate left its queue");
    let synced = accelcal_ok(&["lot", "sync", &url, "--queue", &queue.dir.to_string_lossy()]);
    assert!(synced.contains("1 sent"), "{synced}");
    assert_eq!(counted(&url), (2, 24, true));
    std::fs::remove_dir_all(&dir).unwrap();
}
