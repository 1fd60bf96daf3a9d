//! The whitened residuals at a state and their Jacobian by forward differences: a model number
//! re-integrates every turn, an orientation only moves its own rows.

use nalgebra::{DMatrix, DVector, Rotation3, Vector3};

use super::integrate::{integrate_turn, Integrated};
use super::params::{columns, difference_step, model_of, orientation_column, MODEL};
use super::residuals::{residuals, Prepared, Usage};
use super::{JointModel, MotionData, Orientation};

/// Step of the forward differences on an orientation, in radians.
const ORIENTATION_STEP: f64 = 1e-7;

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
