//! One turn integrated through a candidate model: the body's rotation from the rest before to the
//! rest after, and the integral of the specific force carried into the first rest's body frame.
//!
//! NOTE: the rotation over each sample interval uses the mean of its two end rates (a rate taken at
//! the interval's start would lag by half a sample, 0.5 ms at 1 kHz: a bias the skew would have to
//! absorb), shifted by the skew: w(t + skew) ~ w + skew dw/dt. The force integral is the trapezoid
//! rule; at rest at both ends every derivative of the integrand vanishes there, so its error is far
//! below the noise (Euler-Maclaurin).

use nalgebra::{UnitQuaternion, Vector3};

use super::{JointModel, MotionData};

/// What a turn integrates to.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Integrated {
    /// The rotation from the body at the turn's start to the body at its end (R_after = R_before q).
    pub turned: UnitQuaternion<f64>,
    /// The integral of the calibrated specific force over the turn in the body frame of its start,
    /// in g s.
    pub force_integral_gs: Vector3<f64>,
    /// The turn's length D, in seconds.
    pub seconds: f64,
}

/// Turn `k` (after rest `k`) of `data` integrated through `model`.
pub fn integrate_turn(model: &JointModel, data: &MotionData, k: usize) -> Integrated {
    let range = data.turn(k);
    let dt = data.interval_s();
    let forces: Vec<Vector3<f64>> = data.accel_g[range.clone()].iter().map(|m| model.specific_force_g(m)).collect();
    let rates: Vec<Vector3<f64>> =
        data.gyro_dps[range.clone()].iter().zip(&forces).map(|(w, f)| model.rate_rad(w, f)).collect();
    let mut turned = UnitQuaternion::identity();
    let mut sum = forces[0] * 0.5;
    for i in 1..forces.len() {
        let rate = (rates[i - 1] + rates[i]) * 0.5 + (rates[i] - rates[i - 1]) * (model.skew_s / dt);
        turned *= UnitQuaternion::from_scaled_axis(rate * dt);
        let weight = if i + 1 == forces.len() { 0.5 } else { 1.0 };
        sum += turned.transform_vector(&forces[i]) * weight;
    }
    Integrated { turned, force_integral_gs: sum * dt, seconds: (forces.len() - 1) as f64 * dt }
}
