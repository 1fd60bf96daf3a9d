//! A person at the board, played over `accelcal sim --pty`: the test reads what `calibrate` tells
//! the person on stderr and turns the simulated board through the simulator's stdin, as a person
//! would; it declines, presses Ctrl-C, pulls the cable and resumes.

use std::process::{Command, Output};
use std::time::Duration;

mod common;

use common::person::{Moves, Run};
use common::SimPty;

fn accelcal(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_accelcal")).args(args).output().expect("accelcal runs")
}

/// `accelcal sim --pty` with `seed`, lying on the desk at no wanted orientation: only the person's
/// turns bring it to one.
fn board_on_the_desk(seed: &str) -> SimPty {
    let mut sim = SimPty::with_seed(seed, &[]);
    sim.tell("place 0.3 0.4 0.866");
    sim
}

/// The board's active and stored calibration, as `download` prints them.
fn calibrations(sim: &SimPty) -> (String, String) {
    let active = accelcal(&["download", "--port", &sim.path]);
    let stored = accelcal(&["download", "--port", &sim.path, "--stored"]);
    (String::from_utf8(active.stdout).unwrap(), String::from_utf8(stored.stdout).unwrap())
}

/// `accelcal calibrate --chip-fit` against the simulated board, the person placing it.
fn quick_run(port: &str, extra: &[&str]) -> Run {
    let args = [&["--chip-fit", "--seconds", "5", "--verify", "2"][..], extra].concat();
    Run::start(port, &args, Moves::Place)
}

fn session_captures(stem: &std::path::Path) -> usize {
    let text = std::fs::read_to_string(stem.with_extension("json")).unwrap();
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    json["captures"].as_array().unwrap().len()
}

fn temp_stem(name: &str) -> std::path::PathBuf {
    std::env::temp_dir().join(format!("accelcal-person-{}-{name}", std::process::id()))
}

fn declining_the_upload_leaves_the_active_and_stored_calibration_as_they_were() {
    let mut sim = board_on_the_desk("11");
    let kept = r#"{"model": "six-position", "matrix": [[1.01,0,0],[0,0.99,0],[0,0,1]], "offset": [0.02, -0.01, 0.03]}"#;
    let file = temp_stem("kept.json");
    std::fs::write(&file, kept).unwrap();
    assert!(accelcal(&["upload", "--port", &sim.path, file.to_str().unwrap(), "--save"]).status.success());
    let before = calibrations(&sim);
    assert!(before.0.contains("0.0299999") && before.1.contains("0.0299999"), "{before:?}");
    let session = temp_stem("declined");
    let run = quick_run(&sim.path.clone(), &["--session", session.to_str().unwrap()]);
    let (status, _, stderr) = run.finish(&mut sim);
    assert!(status.success(), "{stderr}");
    assert!(stderr.contains("not uploaded; the board keeps its previous calibration"), "{stderr}");
    assert_eq!(calibrations(&sim), before, "declining changed the board");
}

fn ctrl_c_keeps_the_captures_so_far_and_resume_completes_them_to_a_verified_calibration() {
    let mut sim = board_on_the_desk("12");
    let session = temp_stem("interrupted");
    let mut run = quick_run(&sim.path.clone(), &["--session", session.to_str().unwrap()]);
    assert!(run.follow(&mut sim, "captured 2 of 10").is_some(), "{:?}", run.seen);
    // The person stops instead of turning the board to the third face.
    std::thread::sleep(Duration::from_millis(300));
    run.interrupt();
    let (status, _, stderr) = run.finish(&mut sim);
    assert!(!status.success(), "exit 0 after Ctrl-C: {stderr}");
    let last = stderr.lines().last().unwrap();
    assert!(last.contains("interrupted (Ctrl-C)") && last.contains("2 captures so far are kept in"), "{last}");
    assert!(last.contains(&format!("--resume {}", session.with_extension("json").display())), "{last}");
    assert_eq!(session_captures(&session), 2);

    let json = session.with_extension("json");
    let run = quick_run(&sim.path.clone(), &["--resume", json.to_str().unwrap(), "--yes"]);
    let (status, stdout, stderr) = run.finish(&mut sim);
    assert!(status.success(), "{stderr}");
    assert!(stderr.contains("2 of 10 positions captured"), "{stderr}");
    assert!(stdout.starts_with("verified at 2 fresh orientations"), "{stdout}");
    // The first captures were taken in the interrupted run: no board time is claimed for the session.
    assert!(!stdout.contains("the board was kept"), "{stdout}");
    assert_eq!(session_captures(&session), 10);
}

fn a_pulled_cable_keeps_the_captures_so_far_and_resume_on_another_board_is_refused_by_serial() {
    let mut sim = board_on_the_desk("13");
    let session = temp_stem("pulled");
    let mut run = quick_run(&sim.path.clone(), &["--session", session.to_str().unwrap()]);
    assert!(run.follow(&mut sim, "captured 3 of 10").is_some(), "{:?}", run.seen);
    drop(sim); // the cable is pulled
    let mut other = board_on_the_desk("14");
    let (status, _, stderr) = run.finish(&mut other);
    assert!(!status.success());
    assert!(stderr.lines().last().unwrap().contains("3 captures so far are kept in"), "{stderr}");
    assert_eq!(session_captures(&session), 3);

    let json = session.with_extension("json");
    let output = accelcal(&["calibrate", "--port", &other.path, "--resume", json.to_str().unwrap(), "--yes"]);
    assert!(!output.status.success());
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert!(stderr.contains("was captured on another board (serial "), "{stderr}");
    assert_eq!(session_captures(&session), 3, "the refused resume changed the session");
}

fn a_session_in_a_missing_directory_is_refused_before_the_first_capture() {
    let sim = board_on_the_desk("15");
    let output = accelcal(&["calibrate", "--port", &sim.path, "--session", "/nonexistent-dir/s", "--yes"]);
    assert!(!output.status.success());
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert!(stderr.contains("cannot write /nonexistent-dir/s.json"), "{stderr}");
    assert!(!stderr.contains("found; averaging"), "{stderr}");
}

fn ctrl_c_during_the_verification_says_the_calibration_is_already_uploaded_and_saved() {
    let mut sim = board_on_the_desk("16");
    let session = temp_stem("verifying");
    let mut run = quick_run(&sim.path.clone(), &["--yes", "--session", session.to_str().unwrap()]);
    assert!(run.follow(&mut sim, "uploaded and saved; now checking").is_some(), "{:?}", run.seen);
    std::thread::sleep(Duration::from_millis(300));
    run.interrupt();
    let (status, _, stderr) = run.finish(&mut sim);
    assert!(!status.success(), "exit 0 after Ctrl-C: {stderr}");
    let last = stderr.lines().last().unwrap();
    assert!(
        last.contains("interrupted (Ctrl-C)") && last.contains("already uploaded and saved on the board"),
        "{last}"
    );
    assert!(last.contains(&format!("accelcal verify --port {}", sim.path)), "{last}");
    let (active, stored) = calibrations(&sim);
    assert_eq!(active, stored, "what is active is what is saved");
    let kept: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(session.with_extension("json")).unwrap()).unwrap();
    let active: serde_json::Value = serde_json::from_str(&active).unwrap();
    let offsets = |v: &serde_json::Value| v.as_array().map(|a| a.iter().filter_map(|x| x.as_f64()).collect::<Vec<_>>());
    let (kept, active) =
        (offsets(&kept["uploaded"]["offset_g"]).unwrap_or_default(), offsets(&active["offset"]).unwrap());
    assert_eq!(kept.len(), 3, "the session does not say what the board holds");
    // NOTE: the board holds f32; the session keeps the same f32 values.
    assert!(kept.iter().zip(&active).all(|(k, a)| (k - a).abs() < 1e-7), "{kept:?} against {active:?}");
}

/// A known calibration uploaded to the board and saved (kept in a file named after `name`).
fn upload_and_save(sim: &SimPty, name: &str) {
    let kept = r#"{"model": "six-position", "matrix": [[1.01,0,0],[0,0.99,0],[0,0,1]], "offset": [0.02, -0.01, 0.03]}"#;
    let file = temp_stem(&format!("{name}.json"));
    std::fs::write(&file, kept).unwrap();
    assert!(accelcal(&["upload", "--port", &sim.path, file.to_str().unwrap(), "--save"]).status.success());
}

fn ctrl_c_during_verify_says_what_was_verified_and_leaves_the_board_as_it_was() {
    let mut sim = board_on_the_desk("17");
    upload_and_save(&sim, "verified");
    let before = calibrations(&sim);
    let mut run = Run::command(&["verify", "--port", &sim.path.clone(), "--positions", "3"], Moves::Place);
    assert!(run.follow(&mut sim, "verification 1:").is_some(), "{:?}", run.seen);
    assert!(run.follow(&mut sim, "Verification 2").is_some(), "{:?}", run.seen);
    std::thread::sleep(Duration::from_millis(1500));
    run.interrupt();
    let (status, _, stderr) = run.finish(&mut sim);
    assert!(!status.success(), "exit 0 after Ctrl-C: {stderr}");
    let last = stderr.lines().last().unwrap();
    assert!(last.contains("interrupted (Ctrl-C)") && last.contains("1 of 3 orientations verified"), "{last}");
    assert!(last.contains("its calibration is as it was"), "{last}");
    // The board answers at once (its capture was cancelled, not left running) and holds what it held.
    assert_eq!(calibrations(&sim), before, "verify changed the board");
}

fn a_verification_capture_the_board_moved_during_waits_for_a_fresh_orientation_again() {
    let mut sim = board_on_the_desk("18");
    upload_and_save(&sim, "moved");
    let mut run = Run::command(&["verify", "--port", &sim.path.clone(), "--positions", "2"], Moves::Place);
    assert!(run.follow(&mut sim, "verification 1:").is_some(), "{:?}", run.seen);
    assert!(run.follow(&mut sim, "Verification 2").is_some(), "{:?}", run.seen);
    // A knock 3 s after the board was set down: inside its 5 s capture (the wait takes about one second).
    std::thread::sleep(Duration::from_secs(3));
    sim.tell("shake 0.3 0.3");
    let knocked = run.lines_for(Duration::from_secs(8));
    assert!(knocked.iter().any(|l| l.contains("moved during the capture")), "{:?}", run.seen);
    // The person sets it down where verification 1 was made: that is not fresh, so no check there.
    sim.tell("place 0.707 0 0.707");
    let there = run.lines_for(Duration::from_secs(10));
    assert!(!there.iter().any(|l| l.contains("verification 2:")), "verified where it had verified: {there:?}");
    sim.tell("place -0.707 0.707 0");
    assert!(run.follow(&mut sim, "verification 2:").is_some(), "{:?}", run.seen);
    let (status, stdout, stderr) = run.finish(&mut sim);
    assert!(status.success(), "{stderr}");
    assert!(stdout.contains("| |a| - 1 g | rms"), "{stdout}");
}

fn a_session_resumed_after_ctrl_c_in_its_verification_keeps_the_gyro_g_it_uploaded() {
    let mut sim = board_on_the_desk("17");
    let session = temp_stem("resumed-g");
    let json = session.with_extension("json");
    let quick = ["--chip-fit", "--seconds", "5", "--verify", "2", "--yes"];
    let first = [&quick[..], &["--session", session.to_str().unwrap()]].concat();
    let mut run = Run::start(&sim.path.clone(), &first, Moves::Turn);
    assert!(run.follow(&mut sim, "uploaded and saved; now checking").is_some(), "{:?}", run.seen);
    run.interrupt();
    let _ = run.finish(&mut sim);
    let g_of = |text: &str| serde_json::from_str::<serde_json::Value>(text).unwrap()["gyro_matrix"].clone();
    let fitted = g_of(&calibrations(&sim).0);
    assert!(fitted[0][0].as_f64().is_some_and(|s| s != 1.0), "the first run fitted no G: {fitted}");

    let again = [&quick[..], &["--resume", json.to_str().unwrap()]].concat();
    let (_, _, stderr) = Run::start(&sim.path.clone(), &again, Moves::Turn).finish(&mut sim);
    assert!(stderr.contains("G kept from the calibration this session uploaded in an earlier run"), "{stderr}");
    assert_eq!(g_of(&calibrations(&sim).0), fitted, "the resumed run dropped the board's G");
    let kept: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert!(kept["gyro_turns"].as_array().is_some_and(|t| !t.is_empty()), "the session lost its turns");
}

fn a_wait_written_to_a_log_says_what_it_waits_for_every_ten_seconds() {
    let mut sim = board_on_the_desk("17");
    let session = temp_stem("log-wait");
    let mut run = quick_run(&sim.path.clone(), &["--session", session.to_str().unwrap()]);
    // The board lies at no wanted orientation: nothing but the wait happens for these 35 s.
    let lines = run.lines_for(Duration::from_secs(35));
    let waits: Vec<&String> = lines.iter().filter(|l| l.starts_with("waiting: ")).collect();
    assert!((2..=3).contains(&waits.len()), "{} waiting lines in 35 s: {lines:#?}", waits.len());
    assert!(waits.iter().all(|l| l.contains("degrees from")), "{waits:#?}");
    run.interrupt();
    let (status, _, stderr) = run.finish(&mut sim);
    assert!(!status.success(), "{stderr}");
}

fn main() -> std::process::ExitCode {
    common::side_by_side::run(common::side_by_side::scenarios![
        declining_the_upload_leaves_the_active_and_stored_calibration_as_they_were,
        ctrl_c_keeps_the_captures_so_far_and_resume_completes_them_to_a_verified_calibration,
        a_pulled_cable_keeps_the_captures_so_far_and_resume_on_another_board_is_refused_by_serial,
        a_session_in_a_missing_directory_is_refused_before_the_first_capture,
        ctrl_c_during_the_verification_says_the_calibration_is_already_uploaded_and_saved,
        ctrl_c_during_verify_says_what_was_verified_and_leaves_the_board_as_it_was,
        a_verification_capture_the_board_moved_during_waits_for_a_fresh_orientation_again,
        a_session_resumed_after_ctrl_c_in_its_verification_keeps_the_gyro_g_it_uploaded,
        a_wait_written_to_a_log_says_what_it_waits_for_every_ten_seconds,
    ])
}
