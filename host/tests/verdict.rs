//! `calibrate` ends with a verdict against `--target-mg`: reached, or missed with why (a
//! calibration that misses by more than its noise ends the command with status 2: the simulated
//! sessions reach their target, so that is tested in `procedure::verdict`).

mod common;

use std::time::Duration;

fn calibrate(extra: &[&str]) -> (Option<i32>, serde_json::Value, String) {
    let args = [&["calibrate", "--sim", "--yes", "--json"], extra].concat();
    let (output, _) = common::accelcal_within(&args, Duration::from_secs(300));
    let json = serde_json::from_slice(&output.stdout).unwrap_or_default();
    (output.status.code(), json, String::from_utf8_lossy(&output.stderr).into_owned())
}

#[test]
fn a_target_reached_ends_with_status_0_and_says_so() {
    let (code, json, stderr) = calibrate(&["--sim-sensor", "settled", "--target-mg", "2"]);
    assert_eq!(code, Some(0), "{stderr}");
    let target = &json["target"];
    assert_eq!(target["target_mg"], 2.0);
    assert_eq!(target["reached"], true, "{target}");
    assert!(target["line"].as_str().unwrap().ends_with(": reached"), "{target}");
}

#[test]
fn a_fixed_length_calibration_is_judged_trusted_or_not_without_a_target() {
    let (code, json, stderr) = calibrate(&["--quick"]);
    assert_eq!(code, Some(0), "{stderr}");
    let line = json["target"]["line"].as_str().unwrap();
    assert!(json["target"]["target_mg"].is_null() && line.contains("aim at no --target-mg"), "{line}");
}
