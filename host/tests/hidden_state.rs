//! Commands leave the board as they found it, or say what they changed; what a board is shows.

mod common;

use std::time::Duration;

use common::SimPty;

fn accelcal(args: &[&str]) -> std::process::Output {
    common::accelcal_within(args, Duration::from_secs(60)).0
}

fn info_json(port: &str) -> serde_json::Value {
    serde_json::from_slice(&accelcal(&["info", "--port", port, "--json"]).stdout).unwrap()
}

#[test]
fn record_sets_the_board_back_to_the_rate_it_found_and_says_so() {
    let sim = SimPty::with_seed("41", &["--fast"]);
    let found = info_json(&sim.path)["sample_rate_hz"].clone();
    assert_eq!(found, 100);
    let file = std::env::temp_dir().join(format!("accelcal-hidden-{}.npy", std::process::id()));
    let args = ["record", "--port", &sim.path, "--rate", "1000", "--seconds", "2", "-o", file.to_str().unwrap()];
    let output = accelcal(&args);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    assert!(stderr.contains("the board is back at its 100 Hz"), "{stderr}");
    assert_eq!(info_json(&sim.path)["sample_rate_hz"], found, "record left the board at another rate");
    std::fs::remove_file(file).unwrap();
}

#[test]
fn info_shows_the_boards_serial_as_sessions_record_it() {
    let text = String::from_utf8(accelcal(&["info", "--sim", "--seed", "42"]).stdout).unwrap();
    assert!(text.starts_with("board serial 53494D00000000000000002A, firmware "), "{text}");
    let json: serde_json::Value =
        serde_json::from_slice(&accelcal(&["info", "--sim", "--seed", "42", "--json"]).stdout).unwrap();
    assert_eq!(json["serial"], "53494D00000000000000002A");
}
