//! The joint fit of a session that keeps turning (issue 38): the accelerometer, the gyro (scale and
//! misalignment, bias, g-sensitivity) and the accelerometer-gyro timing skew fitted together with the
//! orientation of every rest, the rests linked by the integrated gyro, and each turn's velocity
//! change held at zero (a board at rest at both ends of a turn: the integral of R(t) f(t) dt over it
//! is g D, whatever the hand's linear acceleration). docs/motion.md has the model and the equations.

mod bound;
mod check;
mod integrate;
mod linearise;
mod params;
mod residuals;
mod solve;

use std::ops::Range;

use nalgebra::{DMatrix, Matrix3, Rotation3, Vector3};

use crate::fit::prediction::Prediction;

pub use bound::{bound, Bound, Information};
pub use check::{fit_or_fall_back, usable, MotionOutcome, Unusable};
pub use integrate::{integrate_turn, Integrated};
pub use solve::fit_joint;

/// A session recorded at a fixed rate: every accelerometer sample with its gyro sample.
#[derive(Debug, Clone, PartialEq)]
pub struct MotionData {
    /// Samples per second, in Hz.
    pub rate_hz: f64,
    /// Raw accelerometer readings, in g, one per sample.
    pub accel_g: Vec<Vector3<f64>>,
    /// Raw gyro readings, in deg/s, one per accelerometer sample (empty: the board sent none).
    pub gyro_dps: Vec<Vector3<f64>>,
    /// Each sample's sequence number as the board counted it (a step other than 1 is a gap).
    pub indices: Vec<u64>,
    /// The sample index ranges where the board rested, in time order; a turn lies between two.
    pub rests: Vec<Range<usize>>,
    /// The largest reading the accelerometer's range can give, in g (a reading there may be clipped).
    pub accel_full_scale_g: f64,
    /// The largest reading the gyro's range can give, in deg/s.
    pub gyro_full_scale_dps: f64,
    /// The white noise the fit weighs by.
    pub noise: SensorNoise,
}

impl MotionData {
    /// Seconds between samples.
    pub fn interval_s(&self) -> f64 {
        1.0 / self.rate_hz
    }

    /// The samples of the turn after rest `k`: from the last sample of rest `k` to the first of
    /// rest `k + 1`, both at rest, so the board's velocity is zero at both ends.
    pub fn turn(&self, k: usize) -> Range<usize> {
        self.rests[k].end - 1..self.rests[k + 1].start + 1
    }

    /// The number of turns (one fewer than the rests).
    pub fn turns(&self) -> usize {
        self.rests.len().saturating_sub(1)
    }
}

/// White-noise densities, one-sided, as a datasheet states them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SensorNoise {
    /// Accelerometer noise density, in g/sqrt(Hz).
    pub accel_density_g: f64,
    /// Gyro rate-noise density, in (deg/s)/sqrt(Hz).
    pub gyro_density_dps: f64,
}

impl SensorNoise {
    /// Variance of an accelerometer axis' T-second mean times T, in g^2 s: n^2 / 2 (one-sided density).
    pub fn accel_variance_g2s(&self) -> f64 {
        self.accel_density_g.powi(2) / 2.0
    }

    /// Angle random walk per axis, in rad^2/s: the gyro's n^2 / 2, in radians.
    pub fn angle_walk_rad2_per_s(&self) -> f64 {
        self.gyro_density_dps.to_radians().powi(2) / 2.0
    }

    /// Variance of a gyro axis' T-second mean times T, in (deg/s)^2 s.
    pub fn gyro_variance_dps2s(&self) -> f64 {
        self.gyro_density_dps.powi(2) / 2.0
    }
}

/// The sensor model the joint fit estimates. Calibrated: a = M (m - o), w = G (w_raw - b - S a),
/// and the gyro's samples lag the accelerometer's by `skew_s`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointModel {
    /// M, upper triangular (it fixes the body frame to the accelerometer's x axis and x-y plane).
    pub accel_matrix: Matrix3<f64>,
    /// o, in g.
    pub accel_offset_g: Vector3<f64>,
    /// G, dimensionless.
    pub gyro_matrix: Matrix3<f64>,
    /// b, in deg/s.
    pub gyro_bias_dps: Vector3<f64>,
    /// S, the gyro's g-sensitivity, in deg/s per g.
    pub g_sensitivity_dps_per_g: Matrix3<f64>,
    /// How much later than the accelerometer the gyro's samples are, in seconds.
    pub skew_s: f64,
}

impl JointModel {
    /// The calibrated specific force of a raw reading, in g.
    pub fn specific_force_g(&self, raw_g: &Vector3<f64>) -> Vector3<f64> {
        self.accel_matrix * (raw_g - self.accel_offset_g)
    }

    /// The calibrated rate of a raw gyro reading, in rad/s, given the calibrated specific force.
    pub fn rate_rad(&self, raw_dps: &Vector3<f64>, force_g: &Vector3<f64>) -> Vector3<f64> {
        let corrected = raw_dps - self.gyro_bias_dps - self.g_sensitivity_dps_per_g * force_g;
        (self.gyro_matrix * corrected) * 1f64.to_radians()
    }
}

/// The joint fit's result.
#[derive(Debug, Clone, PartialEq)]
pub struct JointFit {
    /// The fitted sensor model.
    pub model: JointModel,
    /// Each rest's orientation, body to world.
    pub orientations: Vec<Orientation>,
    /// The standard error of each of the model's 31 numbers (M's upper triangle, o, G, b, S, skew).
    pub std_errors: Vec<f64>,
    /// The accelerometer's covariance (M's six, o's three), for predictions.
    pub accel_covariance: DMatrix<f64>,
    /// The error the fit's own uncertainty predicts at a fresh orientation.
    pub prediction: Prediction,
    /// The whitened residuals' sum of squares over their degrees of freedom (1 when the noise is
    /// what the data claim).
    pub chi2_per_dof: f64,
    /// Gauss-Newton steps taken.
    pub iterations: usize,
}

/// The world's up, the direction the specific force points at rest (world z).
pub fn world_up() -> Vector3<f64> {
    Vector3::z()
}

/// A rest's orientation: the rotation from the body frame to the world frame.
pub type Orientation = Rotation3<f64>;

#[cfg(test)]
mod tests;
