//! `accelcal thermal --sim`: the board warms and then cools, the chip bins every sample, and the
//! heating and cooling runs are compared.

use std::process::Command;

#[test]
fn thermal_sim_learns_warming_and_cooling_and_finds_no_hysteresis_in_a_sensor_without_one() {
    let output = Command::new(env!("CARGO_BIN_EXE_accelcal"))
        .args(["thermal", "--sim", "--json", "--seed", "2"])
        .output()
        .unwrap();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    let fit = &json["fit"];
    assert_eq!(fit["points"].as_array().map(Vec::len), fit["bins"].as_u64().map(|n| n as usize), "{}", fit["stopped"]);
    let h = &fit["hysteresis"];
    let overlap = h["overlap_c"][1].as_f64().unwrap() - h["overlap_c"][0].as_f64().unwrap();
    assert!(overlap >= 30.0, "warming and cooling overlap by {overlap} degC: {h}");
    assert!(h["bins"][0].as_u64() >= Some(150) && h["bins"][1].as_u64() >= Some(150), "{h}");
    for k in 0..3 {
        let (difference, error) =
            (h["heating_minus_cooling_mg"][k].as_f64().unwrap(), h["std_error_mg"][k].as_f64().unwrap());
        // NOTE: the simulated sensor has no hysteresis; what differs is the bias wander over the hour
        // between the two passes (1 ug/sqrt(s) random walk, 40 ug Markov), a few tens of ug.
        assert!(difference.abs() < 0.15, "axis {k}: heating minus cooling {difference} mg");
        assert!(error > 0.0 && error < 0.05, "axis {k}: standard error {error} mg");
    }
}
