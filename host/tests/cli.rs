//! The `accelcal` binary as a user runs it: output on success, one line naming the cause on failure.

use std::process::{Command, Output};

fn accelcal(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_accelcal")).args(args).output().expect("accelcal runs")
}

fn phone_data() -> String {
    format!("{}/../tests/data/huawei-phone-13.csv", env!("CARGO_MANIFEST_DIR"))
}

fn write_temp(name: &str, text: &str) -> std::path::PathBuf {
    let path = std::env::temp_dir().join(format!("accelcal-cli-{}-{name}", std::process::id()));
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn fit_json_has_the_fields_of_the_design_interface() {
    let output = accelcal(&["fit", &phone_data(), "--model", "six-position", "--g", "9.81", "--json"]);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).expect("stdout is one JSON object");
    assert_eq!(json["model"], "six-position");
    let matrix = json["matrix"].as_array().unwrap();
    assert_eq!(matrix.len(), 3);
    // A phone accelerometer's scale is within a few percent of unity.
    let m11 = matrix[0][0].as_f64().unwrap();
    assert!((m11 - 1.0).abs() < 0.05, "M11 = {m11}");
    assert_eq!(json["offset"].as_array().unwrap().len(), 3);
    assert!(json["cost"].as_f64().unwrap() > 0.0);
    assert_eq!(json["iterations"], 0);
    assert_eq!(json["std_errors"].as_object().unwrap().len(), 12);
    assert!(json["std_errors"]["o_z"].as_f64().unwrap() > 0.0);
}

#[test]
fn fit_auto_prints_the_richest_fit_with_errors_before_and_after_and_the_comparison() {
    let output = accelcal(&["fit", &phone_data(), "--g", "9.81"]);
    assert!(output.status.success());
    let text = String::from_utf8(output.stdout).unwrap();
    // auto: the richest model 13 orientation-free rows support, then every model for comparison.
    assert!(text.starts_with("model ortho9 (13 of 13 rows used)"), "{text}");
    assert!(text.contains("worst ||a|-g|:"), "{text}");
    assert!(text.contains("model comparison"), "{text}");
    assert!(text.contains("linear12          not supported: linear12 needs at least 4 rows"), "{text}");
}

#[test]
fn a_bad_file_fails_with_one_line_naming_the_line_and_cause() {
    let path = write_temp("bad.csv", "x,y,z\n1,2,3\n1,oops,3\n");
    let output = accelcal(&["fit", path.to_str().unwrap()]);
    assert!(!output.status.success());
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("line 3, column y: \"oops\" is not a number"), "{stderr}");
}

#[test]
fn a_file_without_references_is_refused_for_linear12_with_what_to_add() {
    let output = accelcal(&["fit", &phone_data(), "--model", "linear12", "--g", "9.81"]);
    assert!(!output.status.success());
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert!(
        stderr.contains("linear12 needs at least 4 rows with a known orientation (ref_x,ref_y,ref_z); the file has 0"),
        "{stderr}"
    );
}

#[test]
fn a_missing_file_and_an_unknown_model_are_named() {
    let output = accelcal(&["fit", "/nonexistent/data.csv"]);
    assert!(String::from_utf8(output.stderr).unwrap().contains("cannot read /nonexistent/data.csv"));
    let output = accelcal(&["fit", &phone_data(), "--model", "quadratic"]);
    assert!(!output.status.success());
    assert!(String::from_utf8(output.stderr).unwrap().contains("unknown model \"quadratic\""));
}
