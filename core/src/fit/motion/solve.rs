//! The joint fit: Gauss-Newton from the identity model, each rest's orientation started from its own
//! mean reading (tilt) and the gyro's chain of turns (heading). The Jacobian is `linearise`'s.

use nalgebra::{DVector, Matrix3, Rotation3, Vector3};

use super::integrate::integrate_turn;
use super::linearise::{linearise, State};
use super::params::{orientation_column, vector_of};
use super::residuals::{Prepared, Usage};
use super::{world_up, JointFit, JointModel, MotionData, Orientation};

/// Gauss-Newton steps tried before giving up.
const MAX_ITERATIONS: usize = 30;
/// A step whose squared length in standard errors (d^T F d) is below this has converged: the
/// estimate moved by a tenth of its own uncertainty.
///
/// NOTE: the forward differences leave steps of 3e-4 to 1e-3 at the optimum (measured); a tenth of
/// a standard error costs 1 % of the estimate's variance.
const CONVERGED_STEP: f64 = 1e-2;
/// A step that lowers the whitened sum of squares by less than this has converged too, and the
/// better of the two states is kept.
///
/// NOTE: on a design that leaves a direction poorly determined (a gyro axis a session barely turned
/// about, say) the forward differences' error makes the steps wander by a few tenths of a standard
/// error about the optimum (measured: seed 14 of the one-minute plan, the cost within 0.1 of its
/// least); the sum of squares itself varies by sqrt(2 dof), about 12, from session to session.
const COST_TOLERANCE: f64 = 1e-2;

/// Fits the joint model to `data` (checked by [`super::usable`] first).
pub fn fit_joint(data: &MotionData) -> Option<JointFit> {
    let prepared = Prepared::new(data);
    let mut state = start(data, &prepared);
    let mut last: Option<(f64, State)> = None;
    for iteration in 1..=MAX_ITERATIONS {
        let (r, j) = linearise(&state, data, &prepared, Usage::ALL);
        let cost = r.norm_squared();
        if let Some((last_cost, last_state)) = last.take().filter(|(c, _)| cost > c - COST_TOLERANCE) {
            let best = if cost < last_cost { &state } else { &last_state };
            return super::bound::summarise(best, data, &prepared, iteration - 1);
        }
        let information = j.transpose() * &j;
        let step = information.clone().cholesky()?.solve(&(-(j.transpose() * r)));
        let converged = step.dot(&(&information * &step)) < CONVERGED_STEP;
        last = Some((cost, state.clone()));
        apply(&mut state, &step);
        if converged {
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

/// Moves `state` by a Gauss-Newton `step`: the model's numbers add, each orientation turns.
fn apply(state: &mut State, step: &DVector<f64>) {
    state.model.iter_mut().zip(step.iter()).for_each(|(v, d)| *v += d);
    for (k, rotation) in state.orientations.iter_mut().enumerate() {
        let turn = Vector3::from_fn(|axis, _| orientation_column(k, axis).map_or(0.0, |c| step[c]));
        *rotation = Rotation3::new(turn) * *rotation;
    }
}
