//! `accelcal info` and `accelcal selftest` on the simulated parts, as a user runs them: the part named
//! and its family confirmed by what its offset registers do.

use std::process::Command;

fn accelcal(args: &[&str]) -> (serde_json::Value, String) {
    let output = Command::new(env!("CARGO_BIN_EXE_accelcal")).args(args).output().expect("accelcal runs");
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    assert!(output.status.success(), "{args:?}: {stderr}");
    let stdout = String::from_utf8(output.stdout).unwrap();
    (serde_json::from_str(&stdout).unwrap_or_default(), stdout)
}

#[test]
fn info_json_says_each_simulated_part_is_confirmed_by_the_offset_register_of_its_family() {
    // The own family's x offset register: 0x06 (MPU-6050), 0x77 (MPU-6500 family).
    let parts = [("mpu6050", "MPU-6050", 0x06), ("mpu6500", "MPU-6500", 0x77), ("icm20689", "MPU-6500", 0x77)];
    for (name, family, own) in parts {
        let (json, _) = accelcal(&["info", "--sim", "--sim-part", name, "--json"]);
        assert_eq!(json["family_confirmed_by"], "offset registers", "{name}: {json}");
        let check = &json["family_check"];
        assert_eq!((check["verdict"].as_str(), check["family"].as_str()), (Some("confirmed"), Some(family)), "{name}");
        for step in check["steps"].as_array().unwrap() {
            let (moved, expected) = (step["moved_mg"].as_f64().unwrap(), step["expected_mg"].as_f64().unwrap());
            let wanted = if step["register"] == own { expected } else { 0.0 };
            assert!((moved - wanted).abs() < 5.0, "{name}: {step}");
            assert_eq!(expected.abs(), 125.0, "{name}: {step}");
        }
    }
}

#[test]
fn info_and_selftest_say_the_family_check_in_words() {
    let (_, text) = accelcal(&["info", "--sim", "--sim-part", "unknown72"]);
    let line = text.lines().find(|l| l.starts_with("family: ")).unwrap_or_default();
    assert!(
        line.starts_with("family: MPU-6500 family, confirmed by its offset registers (0x06 (MPU-6050) stepped"),
        "{text}"
    );
    let (_, text) = accelcal(&["selftest", "--sim", "--sim-part", "mpu9250"]);
    assert!(
        text.lines().any(|l| l.starts_with("family: MPU-6500 family, confirmed by its offset registers")),
        "{text}"
    );
    let (json, _) = accelcal(&["selftest", "--sim", "--sim-part", "mpu6050", "--json"]);
    assert_eq!(
        (&json["family_confirmed_by"], &json["family_check"]["verdict"]),
        (&"offset registers".into(), &"confirmed".into())
    );
}
