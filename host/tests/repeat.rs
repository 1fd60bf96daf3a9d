//! `accelcal repeat 20` on the simulated board (issue 28): with nothing the model leaves out, each
//! parameter's spread over the sessions is the spread the sessions predicted (ratio 1 within its
//! sampling error); with a turn-on bias injected, the offsets' excess is that bias.

mod common;

use std::time::Duration;

use common::accelcal_within;

const SESSIONS: f64 = 20.0;

fn repeat(extra: &[&str]) -> serde_json::Value {
    let args = [&["repeat", "20", "--sim", "--sim-sensor", "settled", "--seed", "3", "--json"], extra].concat();
    let (output, _) = accelcal_within(&args, Duration::from_secs(600));
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    serde_json::from_slice(&output.stdout).unwrap()
}

fn number(value: &serde_json::Value) -> f64 {
    value.as_f64().unwrap()
}

/// The standard error of a standard deviation's ratio to its true value over n sessions, when the
/// ratio is 1: 1 / sqrt(2 (n - 1)).
fn ratio_sampling_error(sessions: f64) -> f64 {
    1.0 / (2.0 * (sessions - 1.0)).sqrt()
}

#[test]
fn repeat_20_without_an_unmodelled_effect_gives_a_ratio_of_one_within_its_sampling_error() {
    let report = repeat(&[]);
    assert_eq!(report["sessions"], 20);
    let parameters = report["parameters"].as_object().unwrap();
    assert_eq!(parameters.len(), 9, "the settled sensor does not warm: ortho9's nine, no drift slopes");
    let sigma = ratio_sampling_error(SESSIONS);
    let ratios: Vec<f64> = parameters.values().map(|p| number(&p["ratio"])).collect();
    for (name, p) in parameters {
        let ratio = number(&p["ratio"]);
        assert!((ratio - 1.0).abs() < 3.0 * sigma, "{name}: ratio {ratio:.3}, 1 +- {:.3} expected", 3.0 * sigma);
    }
    // NOTE: pooled over the nine parameters the ratio's sampling error shrinks by 3.
    let pooled = (ratios.iter().map(|r| r * r).sum::<f64>() / ratios.len() as f64).sqrt();
    assert!((pooled - 1.0).abs() < sigma, "pooled ratio {pooled:.3}, 1 +- {sigma:.3} expected ({ratios:.3?})");
}

#[test]
fn repeat_20_reports_an_injected_turn_on_bias_as_the_offsets_excess_within_10_percent() {
    let report = repeat(&["--sim-turn-on-bias-mg", "2"]);
    assert_eq!(number(&report["turn_on_bias_injected_mg"]), 2.0);
    let runs = report["runs"].as_array().unwrap();
    for (axis, name) in ["o_x", "o_y", "o_z"].iter().enumerate() {
        // The bias injected over these 20 power-ons: the spread of the sensor's true offset.
        let truth: Vec<f64> = runs.iter().map(|r| number(&r["true_offset_g"][axis])).collect();
        let mean = truth.iter().sum::<f64>() / SESSIONS;
        let injected = (truth.iter().map(|t| (t - mean).powi(2)).sum::<f64>() / (SESSIONS - 1.0)).sqrt();
        let excess = number(&report["parameters"][name]["excess"]);
        assert!((excess / injected - 1.0).abs() < 0.10, "{name}: excess {excess:e} g, injected {injected:e} g");
        assert!((injected / 2e-3 - 1.0).abs() < 3.0 * ratio_sampling_error(SESSIONS), "{name}: {injected:e} g drawn");
    }
    let s_x = number(&report["parameters"]["s_x"]["ratio"]);
    assert!((s_x - 1.0).abs() < 3.0 * ratio_sampling_error(SESSIONS), "a turn-on bias moved the scale: {s_x}");
}
