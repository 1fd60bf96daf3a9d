//! The joint fit: Gauss-Newton from the identity model, each rest's orientation started from its own
//! mean reading (tilt) and the gyro's chain of turns (heading). The Jacobian is by forward
//! differences: a model number re-integrates every turn, an orientation only moves its own rows.

use nalgebra::{DMatrix, DVector, Matrix3, Rotation3, Vector3};

use super::integrate::{integrate_turn, Integrated};
use super::params::{columns, difference_step, model_of, orientation_column, vector_of, MODEL};
use super::residuals::{residuals, Prepared, Usage};
use super::{world_up, JointModel, MotionData, Orientation};
use crate::fit::prediction::Prediction;

/// Gauss-Newton steps tried before giving up.
const MAX_ITERATIONS: usize = 30;
/// A step whose squared length in standard errors (d^T F d) is below this has converged: the
/// estimate moved by a tenth of its own uncertainty.
///
/// NOTE: the forward differences leave steps of 3e-4 to 1e-3 at the optimum (measured); a tenth of
/// a standard error costs 1 % of the estimate's variance.
const CONVERGED_STEP: f64 = 1e-2;
/// Step of the forward differences on an orientation, in radians.
const ORIENTATION_STEP: f64 = 1e-7;

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

/// Where the fit stands: the model's numbers and the orientations.
#[derive(Debug, Clone)]
pub(super) struct State {
    pub model: Vec<f64>,
    pub orientations: Vec<Orientation>,
}

impl State {
    /// The state's model.
    pub fn joint_model(&self) -> JointModel {
        model_of(&self.model)
    }
}

/// Fits the joint model to `data` (checked by [`super::usable`] first).
pub fn fit_joint(data: &MotionData) -> Option<JointFit> {
    let prepared = Prepared::new(data);
    let mut state = start(data, &prepared);
    for iteration in 1..=MAX_ITERATIONS {
        let (r, j) = linearise(&state, data, &prepared, Usage::ALL);
        let information = j.transpose() * &j;
        let step = information.clone().cholesky()?.solve(&(-(j.transpose() * r)));
        apply(&mut state, &step);
        if step.dot(&(&information * &step)) < CONVERGED_STEP {
            return super::bound::summarise(&state, data, &prepared, iteration);
        }
    }
    None
}

/// The first estimate: the identity model with the first rest's gyro mean as bias; each rest's tilt
/// from its mean reading, its heading from the chain of turns.
fn start(data: &MotionData, prepared: &Prepared) -> State {
    let model = JointModel {
        accel_matrix: Matrix3::identity(),
        accel_offset_g: Vector3::zeros(),
        gyro_matrix: Matrix3::identity(),
        gyro_bias_dps: prepared.gyro_means_dps[0],
        g_sensitivity_dps_per_g: Matrix3::zeros(),
        skew_s: 0.0,
    };
    let level = |rotation: Orientation, k: usize| {
        let up_now = rotation * prepared.accel_means_g[k].normalize();
        Rotation3::rotation_between(&up_now, &world_up()).unwrap_or_else(Rotation3::identity) * rotation
    };
    let mut orientations = vec![level(Rotation3::identity(), 0)];
    for k in 0..data.turns() {
        let carried = orientations[k] * integrate_turn(&model, data, k).turned.to_rotation_matrix();
        orientations.push(level(carried, k + 1));
    }
    State { model: vector_of(&model), orientations }
}

/// Every turn integrated through `model`.
pub(super) fn integrate_all(model: &JointModel, data: &MotionData) -> Vec<Integrated> {
    (0..data.turns()).map(|k| integrate_turn(model, data, k)).collect()
}

/// The whitened residuals at `state` and their Jacobian (columns: the model's numbers, then the
/// orientations as [`orientation_column`] places them).
pub(super) fn linearise(
    state: &State,
    data: &MotionData,
    prepared: &Prepared,
    usage: Usage,
) -> (DVector<f64>, DMatrix<f64>) {
    let model = state.joint_model();
    let turns = integrate_all(&model, data);
    let r = residuals(&model, &state.orientations, &turns, data, prepared, usage);
    let mut j = DMatrix::zeros(r.len(), columns(data.rests.len()));
    for p in 0..MODEL {
        let mut moved = state.model.clone();
        moved[p] += difference_step(p);
        let moved_model = model_of(&moved);
        let moved_turns = integrate_all(&moved_model, data);
        let moved_r = residuals(&moved_model, &state.orientations, &moved_turns, data, prepared, usage);
        j.set_column(p, &((moved_r - &r) / difference_step(p)));
    }
    for k in 0..state.orientations.len() {
        for (axis, column) in (0..3).filter_map(|axis| orientation_column(k, axis).map(|c| (axis, c))) {
            let mut orientations = state.orientations.clone();
            orientations[k] = Rotation3::new(Vector3::ith(axis, ORIENTATION_STEP)) * orientations[k];
            let moved_r = residuals(&model, &orientations, &turns, data, prepared, usage);
            j.set_column(column, &((moved_r - &r) / ORIENTATION_STEP));
        }
    }
    (r, j)
}

/// Moves `state` by a Gauss-Newton `step`: the model's numbers add, each orientation turns.
fn apply(state: &mut State, step: &DVector<f64>) {
    state.model.iter_mut().zip(step.iter()).for_each(|(v, d)| *v += d);
    for (k, rotation) in state.orientations.iter_mut().enumerate() {
        let turn = Vector3::from_fn(|axis, _| orientation_column(k, axis).map_or(0.0, |c| step[c]));
        *rotation = Rotation3::new(turn) * *rotation;
    }
}
