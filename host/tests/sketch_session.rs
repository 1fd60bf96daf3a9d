//! A session from a board's own stream is kept as it goes (issue 24): Ctrl-C and a pulled cable
//! (the replay killed) leave every still period so far in the session file and every line in its
//! log, and `--resume` goes on with the same session, appending to the same log.

mod common;

use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use common::{accelcal_within, wait_or_kill, SimPty};

/// Longer than a few still periods of the CSV sketch (one every 8-11 s).
const LIMIT: Duration = Duration::from_secs(120);

fn calibrate(args: &[&str]) -> Child {
    Command::new(env!("CARGO_BIN_EXE_accelcal"))
        .arg("calibrate")
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap()
}

fn session(json: &Path) -> serde_json::Value {
    std::fs::read_to_string(json).ok().and_then(|text| serde_json::from_str(&text).ok()).unwrap_or_default()
}

fn captures(json: &Path) -> usize {
    session(json)["captures"].as_array().map_or(0, Vec::len)
}

/// Waits until the session at `json` holds more than `count` captures.
fn wait_for_captures(json: &Path, count: usize) {
    let started = Instant::now();
    while captures(json) <= count {
        assert!(started.elapsed() < LIMIT, "the session held {} captures after {LIMIT:?}", captures(json));
        std::thread::sleep(Duration::from_millis(250));
    }
}

fn stderr_of(child: Child) -> String {
    String::from_utf8_lossy(&child.wait_with_output().unwrap().stderr).into_owned()
}

#[test]
fn ctrl_c_and_a_pulled_cable_lose_no_still_period_and_resume_goes_on_in_the_same_log() {
    let dir = std::env::temp_dir().join(format!("accelcal-sketch-session-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (stem, json, log) = (dir.join("stream"), dir.join("stream.json"), dir.join("stream.log"));
    let sim = SimPty::with_seed("3", &["--sketch", "csv"]);
    let lot = dir.join("lot.sqlite");
    let (lot_arg, stem_arg) = (lot.to_str().unwrap(), stem.to_str().unwrap());
    let mut first = calibrate(&["--port", &sim.path, "--session", stem_arg, "--serial", "desk-1", "--lot", lot_arg]);
    wait_for_captures(&json, 2);
    let kept = captures(&json);
    Command::new("kill").args(["-INT", &first.id().to_string()]).status().unwrap();
    wait_or_kill(&mut first, Duration::from_secs(30));
    let said = stderr_of(first);
    assert!(said.contains("stopped by Ctrl-C") && said.contains("--resume"), "{said}");
    // Cut short, the session is not certified, and the way on names its lot.
    assert!(said.contains(&format!("--resume {} --lot {lot_arg}", json.display())), "{said}");
    assert!(!stem.with_extension("certificate.json").exists() && !lot.exists(), "a cut-short session was certified");
    // Each position is held until its mean is known to what the target needs, then the person turns on.
    assert!(said.contains("+Z taken (its mean known to "), "{said}");
    assert!(captures(&json) >= kept, "Ctrl-C lost still periods: {} of {kept}", captures(&json));
    assert_eq!(session(&json)["kind"], "stream");
    let before = std::fs::read_to_string(&log).unwrap();
    assert!(before.contains("millis,ax,ay,az,gx,gy,gz"), "the log keeps what the port printed");

    let mut second = calibrate(&["--port", &sim.path, "--resume", json.to_str().unwrap(), "--lot", lot_arg]);
    // Enough still periods to fit (9), not yet every face, corner and fresh orientation.
    wait_for_captures(&json, 9);
    let kept = captures(&json);
    drop(sim);
    wait_or_kill(&mut second, Duration::from_secs(30));
    let said = stderr_of(second);
    assert!(said.contains("the port went away"), "{said}");
    assert!(said.contains("no certificate: the session ended before"), "{said}");
    assert!(!stem.with_extension("certificate.json").exists() && !lot.exists(), "a cut-short session was certified");
    assert!(captures(&json) >= kept, "the pulled cable lost still periods: {} of {kept}", captures(&json));
    let after = std::fs::read_to_string(&log).unwrap();
    assert!(after.starts_with(&before) && after.len() > before.len(), "the resumed run appends to the same log");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_lot_needs_the_serial_a_stream_cannot_name_and_a_board_of_our_own_takes_none() {
    let dir = std::env::temp_dir().join(format!("accelcal-sketch-serial-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (stem, lot) = (dir.join("unnamed"), dir.join("lot.sqlite"));
    let sim = SimPty::with_seed("4", &["--sketch", "csv"]);
    let args = ["calibrate", "--port", &sim.path, "--lot", lot.to_str().unwrap(), "--session", stem.to_str().unwrap()];
    let (refused, _) = accelcal_within(&args, LIMIT);
    let said = String::from_utf8_lossy(&refused.stderr);
    assert!(!refused.status.success() && said.contains("--serial LABEL"), "{said}");
    for path in [lot, stem.with_extension("json"), stem.with_extension("log")] {
        assert!(!path.exists(), "{} was written before the refusal", path.display());
    }
    let (refused, _) = accelcal_within(&["calibrate", "--sim", "--chip-fit", "--yes", "--serial", "B1"], LIMIT);
    let said = String::from_utf8_lossy(&refused.stderr);
    assert!(!refused.status.success() && said.contains("reports its own serial"), "{said}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_live_stream_read_in_the_wrong_unit_ends_early_naming_the_unit_its_values_fit() {
    let dir = std::env::temp_dir().join(format!("accelcal-sketch-unit-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // NOTE: the simulated person's session lasts three minutes; a run that waited for its end would
    // be killed at the limit, so ending within it shows the unit ended the session.
    let limit = Duration::from_secs(60);
    let cases = [
        ("--input-unit", "g", "give --input-unit counts-2g"),
        ("--gyro-unit", "deg/s", "give --gyro-unit counts-250dps"),
    ];
    for (flag, unit, named) in cases {
        let sim = SimPty::with_seed("5", &["--sketch", "csv"]);
        let stem = dir.join(flag.trim_start_matches('-'));
        let args = ["calibrate", "--port", &sim.path, flag, unit, "--session", stem.to_str().unwrap()];
        let (ended, _) = accelcal_within(&args, limit);
        let said = String::from_utf8_lossy(&ended.stderr);
        assert!(!ended.status.success() && said.contains(named), "{flag} {unit}: {said}");
        assert!(!said.contains("orientations") && !said.contains("moved"), "{flag} {unit}: {said}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_new_session_onto_an_existing_log_is_refused_naming_it_and_with_overwrite_starts_it_afresh() {
    let dir = std::env::temp_dir().join(format!("accelcal-sketch-log-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (stem, log) = (dir.join("new"), dir.join("mylog.txt"));
    let earlier = "ax,ay,az\n0.01,0.02,1.00\n";
    std::fs::write(&log, earlier).unwrap();
    let sim = SimPty::with_seed("3", &["--sketch", "csv"]);
    let (stem_arg, log_arg) = (stem.to_str().unwrap(), log.to_str().unwrap());
    let args = ["calibrate", "--port", &sim.path, "--session", stem_arg, "--stream-log", log_arg];
    let (refused, _) = accelcal_within(&args, LIMIT);
    let said = String::from_utf8_lossy(&refused.stderr);
    assert!(!refused.status.success(), "{said}");
    assert!(said.contains(&format!("{log_arg} already exists: give another --stream-log")), "{said}");
    assert!(said.contains("or add --overwrite to replace it"), "{said}");
    assert_eq!(std::fs::read_to_string(&log).unwrap(), earlier, "the refused run changed the log");
    // With --overwrite the new session's log holds its own lines only.
    let mut replacing = calibrate(&[&args[1..], &["--overwrite"]].concat());
    wait_for_captures(&dir.join("new.json"), 0);
    Command::new("kill").args(["-INT", &replacing.id().to_string()]).status().unwrap();
    wait_or_kill(&mut replacing, Duration::from_secs(30));
    let kept = std::fs::read_to_string(&log).unwrap();
    assert!(!kept.contains("0.01,0.02,1.00"), "the earlier session's lines are still in the log");
    assert!(kept.lines().count() > 100, "{} lines", kept.lines().count());
}
