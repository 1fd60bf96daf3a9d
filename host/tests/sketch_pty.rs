//! A board running someone's own sketch, on a pseudo-terminal at the sketch's own pace (a simulated
//! person's three-minute session, `accelcal::sim::replay`): accelcal writes not one byte to it (a
//! MicroPython-style board stops its program on 0x03), `ports` and `info` leave it running, and
//! `calibrate --port` with no flag calibrates from each of the eight sketches' streams, keeping a log
//! that `fit LOG` turns into the same calibration.
//!
//! Real pace: the eight replays run side by side, about three minutes in all. The accuracy over ten
//! sessions per sketch runs on a simulated clock in tests/sketch_streams.rs.

mod common;

use std::time::Duration;

use accelcal::sim::replay::Replay;
use accelcal::sim::sketch::Sketch;
use common::accelcal_within;
use std::sync::atomic::Ordering;

/// Longer than a session (three minutes) and the silence that ends it.
const LIMIT: Duration = Duration::from_secs(240);

fn json(stdout: &[u8]) -> serde_json::Value {
    serde_json::from_slice(stdout).unwrap_or_else(|e| panic!("{e}: {}", String::from_utf8_lossy(stdout)))
}

/// `calibrate --port` on the replay, then `fit` on the log it kept: both JSON objects.
fn calibrate_and_refit(sketch: Sketch, path: &str, log: &str) -> (serde_json::Value, serde_json::Value) {
    let args = ["calibrate", "--port", path, "--yes", "--json", "--stream-log", log];
    let (live, _) = accelcal_within(&args, LIMIT);
    assert!(live.status.success(), "{sketch:?}: {}", String::from_utf8_lossy(&live.stderr));
    let (refit, _) = accelcal_within(&["fit", log, "--model", "ortho9", "--json"], LIMIT);
    assert!(refit.status.success(), "{sketch:?}: {}", String::from_utf8_lossy(&refit.stderr));
    (json(&live.stdout), json(&refit.stdout))
}

fn dialect(sketch: Sketch) -> (&'static str, &'static str) {
    match sketch {
        Sketch::I2cdevlib => ("i2cdevlib", "counts-2g"),
        Sketch::Motioncal => ("motioncal", "motioncal-counts"),
        Sketch::Plotter => ("adafruit-plotter", "m/s2"),
        Sketch::Csv => ("csv", "counts-2g"),
        Sketch::Micropython => ("micropython", "g"),
        Sketch::SerialPlotter => ("serial-plotter", "counts-2g"),
        Sketch::Whitespace => ("whitespace", "counts-2g"),
        Sketch::Kalibr => ("kalibr", "m/s2"),
    }
}

#[test]
fn every_sketchs_stream_is_calibrated_live_with_no_flag_and_no_byte_written() {
    let dir = std::env::temp_dir().join(format!("accelcal-sketch-pty-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let replays: Vec<(Sketch, Replay)> =
        Sketch::ALL.into_iter().map(|s| (s, Replay::spawn(s, 7, 1.0).expect("a pseudo-terminal"))).collect();
    let micropython = &replays.iter().find(|(s, _)| *s == Sketch::Micropython).unwrap().1;
    let (ports, _) = accelcal_within(&["ports"], LIMIT);
    assert!(ports.status.success());
    let (info, _) = accelcal_within(&["info", "--port", &micropython.path], LIMIT);
    let refusal = String::from_utf8_lossy(&info.stderr);
    assert!(
        !info.status.success() && refusal.contains("prints on its own") && refusal.contains("wrote nothing"),
        "{refusal}"
    );
    let runs: Vec<_> = replays
        .iter()
        .map(|(sketch, replay)| {
            let (sketch, path) = (*sketch, replay.path.clone());
            let log = dir.join(format!("{sketch:?}.log")).display().to_string();
            std::thread::spawn(move || (sketch, calibrate_and_refit(sketch, &path, &log)))
        })
        .collect();
    for run in runs {
        let (sketch, (live, refit)) = run.join().unwrap();
        let replay = &replays.iter().find(|(s, _)| *s == sketch).unwrap().1;
        assert_eq!(replay.state.written.load(Ordering::SeqCst), 0, "{sketch:?}: bytes were written to the board");
        assert!(!replay.state.stopped.load(Ordering::SeqCst));
        assert!(replay.state.printed.load(Ordering::SeqCst) > 1000, "{sketch:?}: the program did not keep running");
        let (name, unit) = dialect(sketch);
        assert_eq!((live["dialect"].as_str(), live["input_unit"].as_str()), (Some(name), Some(unit)), "{sketch:?}");
        let segments = live["segments"].as_array().unwrap();
        assert!(segments.len() >= 12, "{sketch:?}: {} segments", segments.len());
        for key in ["dialect", "input_unit", "segments", "matrix", "offset"] {
            assert_eq!(live[key], refit[key], "{sketch:?}: {key} differs between the live session and fit LOG");
        }
    }
}
