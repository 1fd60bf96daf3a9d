//! The real Pico binary, as `cargo xtask dist` builds it (dist/accelcal-pico.uf2), run by the
//! rp2040js emulator with the project's simulated MPU-6050 on its I2C bus and its USB serial port on
//! a pseudo-terminal (`accelcal sim --pty --pico`), driven by the unmodified host.
//!
//! Needs Node.js, `npm ci` in boards/pico/emulator and the UF2; without them each test is listed as
//! ignored with what to do (CI=true, where .ci/run installs and builds them, requires them).

use std::time::Duration;

mod common;

use accelcal::calibration::CalibrationJson;
use accelcal::sim::{SimBoard, SimSensor};
use common::person::{Moves, Run};
use common::{accelcal_within, EmulatedPico};
use shared::calibration::{AccelRange, Calibration};

fn json(args: &[&str]) -> serde_json::Value {
    let (output, _) = accelcal_within(args, Duration::from_secs(120));
    assert!(output.status.success(), "{args:?}: {}", String::from_utf8_lossy(&output.stderr));
    serde_json::from_slice(&output.stdout).unwrap()
}

#[test]
#[cfg_attr(
    not(has_pico_emulator),
    ignore = "needs node, `npm ci` in boards/pico/emulator and `cargo xtask dist` (CI=true runs it)"
)]
fn the_real_pico_binary_answers_info_and_streams_the_simulated_sensor_over_its_usb_port() {
    let mut pico = EmulatedPico::boot("3");
    let info = json(&["info", "--port", &pico.path, "--json"]);
    assert_eq!(info["protocol_version"], shared::protocol::PROTOCOL_VERSION, "{info}");
    assert_eq!(info["part"], "MPU-6050", "{info}");
    assert_eq!(info["who_am_i"], 0x68, "{info}");
    assert_eq!(info["sensor"]["address"], 0x68, "{info}");
    assert_eq!(info["serial"].as_str().unwrap().len(), 24, "{info}");
    // The samples come from the simulated sensor over the emulated I2C bus: turned -X up, the
    // accelerometer's x reads about -1 g (the sensor's own errors are a few per cent at most).
    pico.tell("place -X");
    let (output, _) = accelcal_within(&["stream", "--port", &pico.path, "--count", "10"], Duration::from_secs(120));
    let csv = String::from_utf8(output.stdout).unwrap();
    let rows: Vec<Vec<f64>> = csv.lines().skip(1).map(|l| l.split(',').map(|v| v.parse().unwrap()).collect()).collect();
    assert_eq!(rows.len(), 10, "{csv}");
    for row in &rows {
        assert!((row[2] + 1.0).abs() < 0.1 && row[3].abs() < 0.1 && row[4].abs() < 0.1, "not -X up: {row:?}");
    }
}

fn temp_stem(name: &str) -> std::path::PathBuf {
    std::env::temp_dir().join(format!("accelcal-pico-{}-{name}", std::process::id()))
}

/// The true error of the calibration in `calibrate --json`'s output against the realistic simulated
/// sensor of `seed`, at the temperature the calibration was made at (`SimBoard::true_error_mg`).
fn true_error_mg(seed: u64, output: &serde_json::Value) -> f64 {
    let record = CalibrationJson::from_text(&output.to_string()).unwrap();
    true_error_of(seed, &record.to_device(AccelRange::G2).unwrap())
}

fn true_error_of(seed: u64, calibration: &Calibration) -> f64 {
    let (_, board) = SimBoard::in_process(seed, SimSensor::Realistic).unwrap();
    board.true_error_mg(calibration, calibration.mean_temp_c)
}

/// The default calibration of the simulated sensor of `seed` in this process (`calibrate --sim`),
/// as `calibrate --json` prints it.
fn in_process_calibration(seed: u64) -> serde_json::Value {
    let session = temp_stem(&format!("in-process-{seed}"));
    let seed = seed.to_string();
    let args = ["calibrate", "--sim", "--seed", &seed, "--yes", "--json", "--session", session.to_str().unwrap()];
    let (output, _) = accelcal_within(&args, Duration::from_secs(300));
    // NOTE: exit status 2 is a calibration uploaded and saved that missed --target-mg: it is compared all the same.
    assert!(matches!(output.status.code(), Some(0 | 2)), "{}", String::from_utf8_lossy(&output.stderr));
    serde_json::from_slice(&output.stdout).unwrap()
}

/// The board's active calibration as `download --json` prints it (matrix and offset).
fn active_calibration(path: &str) -> serde_json::Value {
    let downloaded = json(&["download", "--port", path]);
    serde_json::json!({ "matrix": downloaded["matrix"], "offset": downloaded["offset"] })
}

#[test]
#[cfg_attr(
    not(has_pico_emulator),
    ignore = "needs node, `npm ci` in boards/pico/emulator and `cargo xtask dist` (CI=true runs it)"
)]
fn the_default_calibration_on_the_real_pico_binary_is_as_good_as_in_process_and_survives_a_power_cycle() {
    const SEED: u64 = 21;
    let mut pico = EmulatedPico::boot(&SEED.to_string());
    pico.tell("place 0.3 0.4 0.866"); // on the desk, at no wanted orientation
    let session = temp_stem("default");
    let args = ["--yes", "--json", "--session", session.to_str().unwrap()];
    let (status, stdout, stderr) = Run::start(&pico.path.clone(), &args, Moves::Turn).finish(&mut pico);
    assert!(matches!(status.code(), Some(0 | 2)), "{stderr}");
    let on_the_pico: serde_json::Value = serde_json::from_str(&stdout).unwrap();

    let in_process = in_process_calibration(SEED);
    let (pico_mg, sim_mg) = (true_error_mg(SEED, &on_the_pico), true_error_mg(SEED, &in_process));
    println!("true error: {pico_mg:.3} mg on the emulated Pico, {sim_mg:.3} mg in process (seed {SEED})");
    assert!(pico_mg <= 1.5 * sim_mg, "{pico_mg:.3} mg on the Pico, {sim_mg:.3} mg in process");
    // NOTE: the three-orientation verification judged as the true error is: against the in-process
    // session's for the same sensor (seed 21's says 0.52 mg in process, its true error 0.30 mg).
    let verified = |output: &serde_json::Value| output["verification"]["after_rms_mg"].as_f64().unwrap();
    let (pico_verified, sim_verified) = (verified(&on_the_pico), verified(&in_process));
    assert!(
        pico_verified <= 1.5 * sim_verified,
        "{pico_verified:.3} mg verified on the Pico, {sim_verified:.3} mg in process"
    );

    // Uploaded and saved: after a power cycle the chip starts from its flash with it active.
    let uploaded = active_calibration(&pico.path);
    assert_eq!(uploaded["offset"], on_the_pico["calibration"]["offset"], "not what calibrate uploaded");
    pico.tell("restart");
    pico.path = pico.next_path();
    assert_eq!(active_calibration(&pico.path), uploaded, "the calibration did not survive the power cycle");
}

/// Seed 22's default calibration in process has a true error of 0.153 mg; six resumed sessions on
/// the emulated Pico had 0.144-0.245 mg. Their three-orientation verification said 0.11-0.39 mg
/// (noise subtracted), uncorrelated with the truth, above the 0.2 mg target in four of the six (exit
/// 2; the in-process session's says 0.49 mg), so the test judges the resumed calibration by its true
/// error, not by that exit status. A resume that lost or mixed up captures is off by far more.
const RESUMED_WITHIN: f64 = 2.0;

#[test]
#[cfg_attr(
    not(has_pico_emulator),
    ignore = "needs node, `npm ci` in boards/pico/emulator and `cargo xtask dist` (CI=true runs it)"
)]
fn a_pulled_usb_cable_mid_session_keeps_the_captures_and_resume_on_the_replugged_pico_completes_them() {
    const SEED: u64 = 22;
    let mut pico = EmulatedPico::boot(&SEED.to_string());
    pico.tell("place 0.3 0.4 0.866");
    let session = temp_stem("pulled");
    let args = ["--yes", "--session", session.to_str().unwrap()];
    let mut run = Run::start(&pico.path.clone(), &args, Moves::Turn);
    for _ in 0..3 {
        assert!(run.follow(&mut pico, "its mean is known to").is_some(), "{:?}", run.seen);
    }
    pico.tell("cable out");
    let (status, _, stderr) = run.finish(&mut pico);
    assert!(!status.success(), "{stderr}");
    let last = stderr.lines().last().unwrap();
    assert!(last.contains("captures so far are kept in"), "{stderr}");
    let kept = session_file(&session)["captures"].as_array().unwrap().clone();
    assert!(kept.len() >= 2, "{} captures kept: {stderr}", kept.len());

    pico.tell("cable in");
    pico.path = pico.next_path();
    let json_path = session.with_extension("json");
    let resume = ["--resume", json_path.to_str().unwrap(), "--yes"];
    let (status, stdout, stderr) = Run::start(&pico.path.clone(), &resume, Moves::Turn).finish(&mut pico);
    // NOTE: exit status 2 is a calibration uploaded and saved whose verification missed --target-mg.
    assert!(matches!(status.code(), Some(0 | 2)), "{stderr}");
    assert!(stderr.contains(&format!("{} of ", kept.len())), "{stderr}");
    assert!(stdout.starts_with("verified at 3 fresh orientations"), "{stdout}");
    let resumed = session_file(&session);
    let captures = resumed["captures"].as_array().unwrap();
    assert!(captures.len() > kept.len() && captures[..kept.len()] == kept[..], "the kept captures were not kept");

    let uploaded: Calibration = serde_json::from_value(resumed["uploaded"].clone()).unwrap();
    let (pico_mg, sim_mg) = (true_error_of(SEED, &uploaded), true_error_mg(SEED, &in_process_calibration(SEED)));
    println!("true error: {pico_mg:.3} mg resumed on the emulated Pico, {sim_mg:.3} mg in process (seed {SEED})");
    assert!(pico_mg <= RESUMED_WITHIN * sim_mg, "{pico_mg:.3} mg resumed, {sim_mg:.3} mg in process");
}

fn session_file(stem: &std::path::Path) -> serde_json::Value {
    let text = std::fs::read_to_string(stem.with_extension("json")).unwrap();
    serde_json::from_str(&text).unwrap()
}
