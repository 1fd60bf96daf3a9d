//! The drift fit on noise-free captures of a known warming sensor.

use shared::linalg;

use super::*;
use crate::orientation::{corners, faces};

/// The adaptive procedure's order of positions (procedure/drift.rs), and +Z again.
const ORDER: [&str; 15] = [
    "+Z", "+X-Y+Z", "+X+Y+Z", "+X+Y-Z", "-X+Y-Z", "-X-Y-Z", "-X-Y+Z", "+X-Y-Z", "-Z", "-X", "-Y", "+X", "+Y", "-X+Y+Z",
    "+Z",
];

/// Noise-free captures of a sensor with M^-1 = diag(1.01, 0.99, 1.02) plus a cross term, offset
/// o(T) = o + c (T - 22), in the adaptive order, warming 0.07 degC a capture, each stating a scatter
/// of `std_g` per sample over 200 samples.
fn warming_captures(slope: Vec3<f64>, std_g: f64) -> Dataset {
    let sensor = [[1.01, 0.002, -0.004], [0.0, 0.99, 0.003], [0.0, 0.0, 1.02]];
    let all = [faces(), corners()].concat();
    let up_of = |name: &str| all.iter().find(|t| t.name == name).map(|t| t.up).unwrap();
    let ups: Vec<[f64; 3]> = ORDER.iter().map(|name| up_of(name)).collect();
    let rows = ups.iter().enumerate().map(|(i, up)| {
        let temp_c = 21.5 + 0.07 * i as f64;
        let offset = linalg::add([0.03, -0.01, -0.08], linalg::scale(slope, temp_c - 22.0));
        let reading = linalg::add(linalg::mul_vec(&sensor, *up), offset);
        Row { line: i + 2, reading, count: Some(200), std: Some([std_g; 3]), temp_c: Some(temp_c), ..Row::default() }
    });
    Dataset { rows: rows.collect() }
}

#[test]
fn the_fitted_drift_is_the_sensor_s_own_and_the_corrected_fit_its_static_calibration() {
    // Captures that say they are known to 0.07 ug: the prior weighs nothing beside them.
    let slope = [0.75e-3, -0.7e-3, 1.4e-3];
    let captures = warming_captures(slope, 1e-6);
    let drift = fitted(&captures).expect("a drift over 1 degC");
    for k in 0..3 {
        assert!((drift.slope_g_per_c[k] - slope[k]).abs() < 2e-6, "{:?} vs {slope:?}", drift.slope_g_per_c);
    }
    // At 22 degC the corrected captures read the static sensor: the fit's offset is o.
    let fit = ortho9(&corrected(&captures, &drift, 22.0)).unwrap();
    for (k, o) in [0.03, -0.01, -0.08].iter().enumerate() {
        assert!((fit.offset[k] - o).abs() < 2e-6, "{:?}", fit.offset);
    }
}

#[test]
fn the_prior_draws_a_slope_from_captures_of_ordinary_noise_towards_zero() {
    // Means known to 0.2 mg, as the default session's: the prior of 1 mg/degC weighs as much as
    // a spare capture or two, so the same slopes come out smaller (measured 0.83, 0.48, 0.91 of
    // the truth), never larger or reversed.
    let slope = [0.75e-3, -0.7e-3, 1.4e-3];
    let drift = fitted(&warming_captures(slope, 2.8e-3)).unwrap();
    for k in 0..3 {
        let ratio = drift.slope_g_per_c[k] / slope[k];
        assert!((0.4..0.95).contains(&ratio), "{:?} vs {slope:?}", drift.slope_g_per_c);
    }
}

#[test]
fn no_drift_is_fitted_when_the_temperature_stayed_or_the_captures_are_too_few() {
    let mut still = warming_captures([1e-3; 3], 2.8e-3);
    still.rows.iter_mut().for_each(|r| r.temp_c = Some(25.0));
    assert_eq!(fitted(&still), None);
    let mut few = warming_captures([1e-3; 3], 2.8e-3);
    few.rows.truncate(DRIFT_MIN_CAPTURES - 1);
    assert_eq!(fitted(&few), None);
}
