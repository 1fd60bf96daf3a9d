//! Integrating one turn: a rotation-vector exponential per sample (exact for a rate constant over
//! the sample interval), never Euler steps on angles.

use nalgebra::{Matrix3, UnitQuaternion, Vector3};
use shared::linalg::Vec3;

/// One turn between two still poses: the raw gyro at full rate and what the poses measured.
#[derive(Debug, Clone, PartialEq)]
pub struct Turn {
    /// Raw angular rate samples, deg/s, one every `interval_s`, none missing.
    pub rates_dps: Vec<Vec3<f64>>,
    /// Time between samples, in seconds.
    pub interval_s: f64,
    /// Gyro bias measured at rest at the pose before, deg/s.
    pub bias_before_dps: Vec3<f64>,
    /// Gyro bias measured at rest at the pose after, deg/s.
    pub bias_after_dps: Vec3<f64>,
    /// Unit up direction in the body frame at the pose before (calibrated accelerometer).
    pub up_before: Vec3<f64>,
    /// Unit up direction in the body frame at the pose after.
    pub up_after: Vec3<f64>,
}

impl Turn {
    /// The bias at sample `i`, interpolated between the two poses' (it drifts slowly).
    pub(super) fn bias_at(&self, i: usize) -> Vector3<f64> {
        let t = (i as f64 + 0.5) / self.rates_dps.len().max(1) as f64;
        let [a, b] = [self.bias_before_dps, self.bias_after_dps].map(Vector3::from);
        a * (1.0 - t) + b * t
    }

    /// The bias-free raw rate of sample `i`, in rad/s.
    pub(super) fn rate_rad(&self, i: usize) -> Vector3<f64> {
        (Vector3::from(self.rates_dps[i]) - self.bias_at(i)) * 1f64.to_radians()
    }
}

/// The rotation from the body at the start of `turn` to the body at its end, with `g` applied.
pub(super) fn integrate(turn: &Turn, g: &Matrix3<f64>) -> UnitQuaternion<f64> {
    (0..turn.rates_dps.len()).fold(UnitQuaternion::identity(), |q, i| {
        q * UnitQuaternion::from_scaled_axis(g * turn.rate_rad(i) * turn.interval_s)
    })
}

/// Where the up direction of the pose before ends up in the body frame after `turn`, with `g`:
/// gravity is fixed in the world, so in the body it turns by the inverse of the body's turn.
pub fn rotate_up(turn: &Turn, g: &Matrix3<f64>) -> Vector3<f64> {
    integrate(turn, g).inverse_transform_vector(&Vector3::from(turn.up_before))
}

/// The angle, in degrees, the body turned through over `turn`, with `g` applied.
pub fn turned_deg(turn: &Turn, g: &Matrix3<f64>) -> f64 {
    integrate(turn, g).angle().to_degrees()
}
