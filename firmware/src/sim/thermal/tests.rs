//! The realistic simulated sensor: warming, drift inside the datasheet's bounds, drift in the samples.

use shared::linalg;

use super::{Environment, ThermalDrift, TRUTH_REF_TEMP_C};
use crate::sim::physics::{Physics, TrueErrors};

#[test]
fn the_die_warms_by_five_degrees_with_a_four_minute_time_constant() {
    let mut env = Environment::powered_on_at(20.0);
    assert_eq!(env.die_c, 20.0);
    env.advance(240.0);
    // One time constant: 1 - 1/e of the 5 degC self-heating.
    assert!((env.die_c - (20.0 + 5.0 * 0.632)).abs() < 0.01, "{}", env.die_c);
    for _ in 0..100 {
        env.advance(12.0);
    }
    assert!((env.die_c - 25.0).abs() < 0.02, "settled at {}", env.die_c); // six time constants
    assert_eq!(env.reading_c() - env.die_c, 1.5, "TEMP_OUT reads 1.5 degC high");
}

#[test]
fn a_ramp_of_the_surroundings_stops_at_its_target_and_the_die_follows() {
    let mut env = Environment::powered_on_at(20.0);
    env.ramp_to(40.0, 0.01);
    for _ in 0..1000 {
        env.advance(1.0);
    }
    assert!((env.ambient_c - 30.0).abs() < 1e-3, "{}", env.ambient_c);
    for _ in 0..4000 {
        env.advance(1.0);
    }
    assert_eq!(env.ambient_c, 40.0);
    assert!((env.die_c - 45.0).abs() < 0.05, "{}", env.die_c);
}

#[test]
fn the_typical_drift_stays_inside_the_datasheet_bounds() {
    let truth = TrueErrors::published_mpu6050();
    let drift = ThermalDrift::typical();
    let offsets: Vec<[f32; 3]> = (0..=70).map(|t| drift.at(&truth, t as f32).offset_g).collect();
    for (axis, bound_mg) in [(0, 35.0), (1, 35.0), (2, 60.0)] {
        let (low, high) = offsets.iter().fold((f32::MAX, f32::MIN), |(l, h), o| (l.min(o[axis]), h.max(o[axis])));
        // Product Specification table 6.2: +-bound over 0-70 degC, i.e. a spread of at most 2 x bound.
        let spread_mg = (high - low) * 1000.0;
        assert!(spread_mg <= 2.0 * bound_mg, "axis {axis}: spread {spread_mg} mg");
        let slope = drift.offset_g[0][axis].abs() * 1000.0;
        assert!((0.5..=2.5).contains(&slope), "axis {axis}: {slope} mg/degC");
        assert!(drift.scale[0][axis].abs() <= 2e-4, "sensitivity drift beyond 0.02 %/degC");
        let gyro = drift.gyro_bias_dps[0][axis].abs();
        assert!((0.04..=0.09).contains(&gyro), "gyro bias drift {gyro} deg/s/degC");
    }
    assert_eq!(drift.at(&truth, TRUTH_REF_TEMP_C), truth, "the static truth holds at 25 degC");
}

/// Mean of the accelerometer and gyro over `n` samples at 100 Hz, with the board up `up`.
fn mean_sample(physics: &mut Physics, up: [f32; 3], n: usize) -> ([f32; 3], [f32; 3], f32) {
    physics.up = up;
    let (mut accel, mut gyro, mut temp) = ([0.0f32; 3], [0.0f32; 3], 0.0);
    for _ in 0..n {
        let s = physics.sample(0.0, 100.0);
        accel = linalg::add(accel, linalg::scale(s.accel_g, 1.0 / n as f32));
        gyro = linalg::add(gyro, linalg::scale(s.gyro_dps, 1.0 / n as f32));
        temp += s.temp_c / n as f32;
    }
    (accel, gyro, temp)
}

#[test]
fn a_warm_realistic_sensor_reads_the_drifted_truth_and_feels_gravity_in_its_gyro() {
    let mut physics = Physics::new(5);
    physics.environment = Environment::fixed(45.0);
    let truth = physics.truth_now();
    let (accel, gyro_up, temp) = mean_sample(&mut physics, [0.0, 0.0, 1.0], 2000);
    // The static truth is 20 degC away: 1.4 mg/degC x 20 + curvature = 25.6 mg on z.
    assert!((truth.offset_g[2] - TrueErrors::published_mpu6050().offset_g[2] - 25.6e-3).abs() < 1e-4);
    let expected = truth.reading_g([0.0, 0.0, 1.0]);
    for axis in 0..3 {
        // 2000 samples at 100 Hz: white noise 400 ug x sqrt(50) / sqrt(2000) = 63 ug, plus wander.
        assert!((accel[axis] - expected[axis]).abs() < 0.4e-3, "axis {axis}: {accel:?} vs {expected:?}");
    }
    assert!((temp - 45.0).abs() < 2e-3, "{temp}"); // f32 sum of 2000 samples
    let (_, gyro_down, _) = mean_sample(&mut physics, [0.0, 0.0, -1.0], 2000);
    // g-sensitivity 0.1 deg/s/g: turning over changes the z rate by 0.2 deg/s.
    let g_effect = (gyro_up[2] - gyro_down[2]) / 2.0;
    assert!((g_effect - 0.1).abs() < 0.01, "g-sensitivity {g_effect}");
}
