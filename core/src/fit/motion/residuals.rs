//! The joint fit's residuals, each divided by its noise (whitened), so that least squares is maximum
//! likelihood and J^T J is the Fisher information.
//!
//! Each rest gives six: its mean specific force against R_k^T up (3) and its mean gyro reading
//! against b + S a (3, the board is still). Each turn gives six: the rest after's orientation against
//! the rest before's carried by the integrated gyro (3, a world-frame rotation vector), and the
//! integral of R f dt against up times D (3). Gyro noise makes the turn's orientation error a random
//! walk e(t) of q per second per axis, which enters both: the link as -e(D) and the integral as
//! -up x (integral of e), so the six are whitened together by their covariance (docs/motion.md).

use nalgebra::{DVector, Matrix3, Matrix6, Vector3, Vector6};

use super::integrate::Integrated;
use super::{world_up, JointModel, MotionData, Orientation};

/// Which of the residuals a computation uses (the bound with less information than the fit's).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Usage {
    /// The rests' gyro means (what fixes the bias and the g-sensitivity).
    pub rest_gyro: bool,
    /// The turns' gyro links between rests.
    pub links: bool,
    /// The turns' zero velocity change.
    pub velocity: bool,
}

impl Usage {
    /// Everything: the joint fit's own.
    pub const ALL: Usage = Usage { rest_gyro: true, links: true, velocity: true };

    /// Rows each rest adds.
    fn rest_rows(&self) -> usize {
        if self.rest_gyro {
            6
        } else {
            3
        }
    }

    /// Rows each turn adds.
    fn turn_rows(&self) -> usize {
        3 * (self.links as usize + self.velocity as usize)
    }

    /// Rows in all for `data`.
    pub fn rows(&self, data: &MotionData) -> usize {
        data.rests.len() * self.rest_rows() + data.turns() * self.turn_rows()
    }
}

/// What the residuals need from the data, computed once: each rest's mean readings and length.
#[derive(Debug, Clone)]
pub(super) struct Prepared {
    pub accel_means_g: Vec<Vector3<f64>>,
    pub gyro_means_dps: Vec<Vector3<f64>>,
    pub rest_seconds: Vec<f64>,
}

impl Prepared {
    /// The rests' means of `data`.
    pub fn new(data: &MotionData) -> Self {
        let mean = |v: &[Vector3<f64>]| v.iter().sum::<Vector3<f64>>() / v.len() as f64;
        Prepared {
            accel_means_g: data.rests.iter().map(|r| mean(&data.accel_g[r.clone()])).collect(),
            gyro_means_dps: data.rests.iter().map(|r| mean(&data.gyro_dps[r.clone()])).collect(),
            rest_seconds: data.rests.iter().map(|r| r.len() as f64 * data.interval_s()).collect(),
        }
    }
}

/// Every residual, whitened, in order: each rest's, then each turn's.
pub(super) fn residuals(
    model: &JointModel,
    orientations: &[Orientation],
    turns: &[Integrated],
    data: &MotionData,
    prepared: &Prepared,
    usage: Usage,
) -> DVector<f64> {
    let mut rows = Vec::with_capacity(usage.rows(data));
    for (k, rotation) in orientations.iter().enumerate() {
        let rest = rest_residual(model, rotation, prepared, k, data);
        rows.extend_from_slice(&rest.as_slice()[..usage.rest_rows()]);
    }
    for (k, turn) in turns.iter().enumerate() {
        let link = turn_residual(&orientations[k], &orientations[k + 1], turn);
        rows.extend(whiten_turn(&link, turn.seconds, data, usage));
    }
    DVector::from_vec(rows)
}

/// Rest `k`'s six whitened residuals: specific force, then gyro.
fn rest_residual(
    model: &JointModel,
    rotation: &Orientation,
    prepared: &Prepared,
    k: usize,
    data: &MotionData,
) -> Vector6<f64> {
    let seconds = prepared.rest_seconds[k];
    let force = model.specific_force_g(&prepared.accel_means_g[k]);
    let accel = (force - rotation.inverse() * world_up()) / (data.noise.accel_variance_g2s() / seconds).sqrt();
    let still = model.gyro_bias_dps + model.g_sensitivity_dps_per_g * force;
    let gyro = (prepared.gyro_means_dps[k] - still) / (data.noise.gyro_variance_dps2s() / seconds).sqrt();
    Vector6::new(accel.x, accel.y, accel.z, gyro.x, gyro.y, gyro.z)
}

/// A turn's link (world rotation vector from the gyro's end to the next rest) and its velocity
/// change (integral of R f dt minus up D, in g s), not yet whitened.
fn turn_residual(before: &Orientation, after: &Orientation, turn: &Integrated) -> Vector6<f64> {
    let carried = before * turn.turned.to_rotation_matrix();
    let link = (after * carried.inverse()).scaled_axis();
    let velocity = before * turn.force_integral_gs - world_up() * turn.seconds;
    Vector6::new(link.x, link.y, link.z, velocity.x, velocity.y, velocity.z)
}

/// The rows `usage` keeps of a turn's residual, whitened by their own covariance.
fn whiten_turn(residual: &Vector6<f64>, seconds: f64, data: &MotionData, usage: Usage) -> Vec<f64> {
    let covariance = turn_covariance(seconds, data);
    let kept: Vec<usize> = (0..6).filter(|&i| if i < 3 { usage.links } else { usage.velocity }).collect();
    let n = kept.len();
    if n == 0 {
        return Vec::new();
    }
    let sub = nalgebra::DMatrix::from_fn(n, n, |a, b| covariance[(kept[a], kept[b])]);
    let r = DVector::from_fn(n, |a, _| residual[kept[a]]);
    // NOTE: the covariance is positive definite (the accelerometer's noise alone makes the velocity
    // block so); solving L z = r whitens by its Cholesky factor.
    match sub.cholesky() {
        Some(c) => c.l().solve_lower_triangular(&r).map(|z| z.as_slice().to_vec()).unwrap_or_default(),
        None => vec![f64::NAN; n],
    }
}

/// The covariance of a turn's (link, velocity) residual of `seconds`: the link q D I; the velocity
/// N^2 D I + [up]x (q D^3 / 3) [up]x^T; between them q D^2 / 2 [up]x^T (docs/motion.md).
fn turn_covariance(seconds: f64, data: &MotionData) -> Matrix6<f64> {
    let q = data.noise.angle_walk_rad2_per_s();
    let up = world_up().cross_matrix();
    let link = Matrix3::identity() * (q * seconds);
    let cross = up.transpose() * (q * seconds.powi(2) / 2.0);
    let velocity = Matrix3::identity() * (data.noise.accel_variance_g2s() * seconds)
        + up * up.transpose() * (q * seconds.powi(3) / 3.0);
    let mut c = Matrix6::zeros();
    c.fixed_view_mut::<3, 3>(0, 0).copy_from(&link);
    c.fixed_view_mut::<3, 3>(0, 3).copy_from(&cross);
    c.fixed_view_mut::<3, 3>(3, 0).copy_from(&cross.transpose());
    c.fixed_view_mut::<3, 3>(3, 3).copy_from(&velocity);
    c
}
