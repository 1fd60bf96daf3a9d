//! The session report: its verdict and its positions as the fit took them.

use shared::linalg;

use super::*;
use crate::orientation::{corners, faces, Orientation};
use crate::session::{CaptureRecord, SessionKind};

fn verified(after_rms_mg: f64, noise_floor_mg: f64) -> Verification {
    Verification::example(after_rms_mg, noise_floor_mg)
}

#[test]
fn a_calibration_is_trusted_within_three_noise_floors_and_only_when_verified() {
    let fit = FitSummary { model: "ortho9", cost: 1e-8, rms_mg: 0.05, parameters: vec![], warnings: vec![] };
    assert!(Verdict::new(&fit, Some(&verified(0.37, 0.125))).trusted);
    assert!(!Verdict::new(&fit, Some(&verified(0.38, 0.125))).trusted);
    let unverified = Verdict::new(&fit, None);
    assert!(!unverified.trusted && unverified.line.contains("not verified"), "{}", unverified.line);
}

/// A noise-free capture at `up` of a sensor read through a scale and offset whose offset drifts by
/// `slope` g/degC from 22 degC, at die temperature `temp_c`.
fn warming_capture(target: &Orientation, temp_c: f64, slope: [f64; 3]) -> CaptureRecord {
    let sensor = [[1.01, 0.0, 0.0], [0.0, 0.99, 0.0], [0.0, 0.0, 1.02]];
    let drifted = linalg::add([0.03, -0.01, -0.08], linalg::scale(slope, temp_c - 22.0));
    let reading = linalg::add(linalg::mul_vec(&sensor, target.up), drifted);
    CaptureRecord::still(target, reading, 1e-6, 200, temp_c)
}

#[test]
fn an_adaptive_session_s_positions_are_shown_with_the_drift_taken_out() {
    // 1 mg/degC over 0.07 degC a capture: the first and last positions read 0.45 mg off the mean
    // temperature's offset; with the drift taken out every calibrated position is on the sphere.
    let targets = [faces(), corners()].concat();
    let slope = [1e-3, -1e-3, 1e-3];
    let captures = targets.iter().enumerate().map(|(i, t)| warming_capture(t, 21.5 + 0.07 * i as f64, slope));
    let session = Session { captures: captures.collect(), kind: SessionKind::Adaptive, ..Session::default() };
    let report = SessionReport::new(&session).unwrap();
    for position in &report.positions {
        assert!(position.residual_after_mg.abs() < 0.01, "{}: {} mg", position.name, position.residual_after_mg);
    }
    // The raw readings are shown as taken, drift and all.
    let first = &report.positions[0];
    assert_eq!(first.raw_g, session.captures[0].stats.mean_g.map(f64::from));
}

#[test]
fn a_session_s_uploaded_record_is_shown_and_calibrates_its_positions() {
    let targets = [faces(), corners()].concat();
    let captures = targets.iter().enumerate().map(|(i, t)| warming_capture(t, 21.5 + 0.07 * i as f64, [1e-3; 3]));
    let mut session = Session { captures: captures.collect(), kind: SessionKind::Adaptive, ..Session::default() };
    let mut record = session.outcome(shared::protocol::SensorConfig::default()).unwrap().calibration;
    record.gyro.matrix[0][1] = 0.0123;
    session.uploaded = Some(record);
    let report = SessionReport::new(&session).unwrap();
    let shown = report.uploaded.as_ref().expect("the uploaded record is shown");
    assert!(shown.line.starts_with("ortho9: scale"), "{}", shown.line);
    assert_eq!(shown.record.gyro_matrix.map(|g| g[0][1]), Some(0.0123f32 as f64), "G as uploaded");
    // The chip's record, its temperature model included, puts every position on the sphere.
    for position in &report.positions {
        assert!(position.residual_after_mg.abs() < 0.01, "{}: {} mg", position.name, position.residual_after_mg);
    }
    // A record 2 mg off in z shows so at +Z and -Z (the refit alone would not).
    record.offset_g[2] += 2e-3;
    session.uploaded = Some(record);
    let report = SessionReport::new(&session).unwrap();
    let worst = report.positions.iter().map(|p| p.residual_after_mg.abs()).fold(0.0, f64::max);
    assert!((1.9..2.1).contains(&worst), "worst {worst} mg");
}
