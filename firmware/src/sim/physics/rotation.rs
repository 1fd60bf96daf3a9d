//! The geometry of the simulated board's turns.

use shared::linalg::{self, Vec3};

/// A hand's turn by `angle_deg` over `span_s`, `seconds` after it began: the angle turned so far
/// in degrees and the rate in deg/s, rate = (angle / span) (1 - cos(2 pi t / span)).
pub(super) fn turning_at(angle_deg: f32, span_s: f32, seconds: f32) -> (f32, f32) {
    if span_s <= 0.0 || seconds >= span_s {
        return (angle_deg, 0.0);
    }
    let phase = 2.0 * core::f32::consts::PI * seconds.max(0.0) / span_s;
    let mean_rate = angle_deg / span_s;
    let turned = mean_rate * (seconds.max(0.0) - span_s * libm::sinf(phase) / (2.0 * core::f32::consts::PI));
    (turned, mean_rate * (1.0 - libm::cosf(phase)))
}

/// Rodrigues' rotation of v about a unit axis by an angle in radians.
pub(super) fn rotate(v: Vec3<f32>, axis: Vec3<f32>, angle: f32) -> Vec3<f32> {
    let (sin, cos) = (libm::sinf(angle), libm::cosf(angle));
    let along = linalg::scale(axis, linalg::dot(axis, v) * (1.0 - cos));
    linalg::add(linalg::add(linalg::scale(v, cos), linalg::scale(linalg::cross(axis, v), sin)), along)
}
