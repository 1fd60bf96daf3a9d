//! The least-squares fit of G: Gauss-Newton over its nine entries, starting from the identity,
//! the Jacobian by forward differences (each column re-integrates every turn).

use nalgebra::{DMatrix, DVector, Matrix3, Vector3};
use shared::linalg::Mat3;

use super::integrate::{rotate_up, Turn};
use super::observability::{informative_turn_deg, missing_axes};
use super::{GyroFit, GyroFitError};
use crate::limits::MIN_GYRO_TURNS;

/// Gauss-Newton steps tried before giving up.
const MAX_ITERATIONS: usize = 20;
/// A step whose largest entry is below this has converged (G is dimensionless).
const STEP_TOLERANCE: f64 = 1e-9;
/// Step of the forward differences on an entry of G (about the square root of f64's epsilon).
const DIFFERENCE_STEP: f64 = 1e-7;

/// Fits G to `turns`; refuses too few turns, or turns that leave an axis unobservable.
pub fn fit_gyro(turns: &[Turn]) -> Result<GyroFit, GyroFitError> {
    if turns.len() < MIN_GYRO_TURNS {
        return Err(GyroFitError::TooFewTurns { turns: turns.len() });
    }
    let turned_deg = informative_turn_deg(turns);
    let axes = missing_axes(&turned_deg);
    if !axes.is_empty() {
        return Err(GyroFitError::Unobservable { axes, turned_deg });
    }
    let mut params = DVector::from_column_slice(Matrix3::<f64>::identity().transpose().as_slice());
    for _ in 0..MAX_ITERATIONS {
        let step = gauss_newton_step(turns, &params).ok_or(GyroFitError::Diverged)?;
        params += &step;
        if step.amax() < STEP_TOLERANCE {
            return summarise(turns, &params);
        }
    }
    Err(GyroFitError::Diverged)
}

/// G from its nine entries, row by row.
fn matrix_of(params: &DVector<f64>) -> Matrix3<f64> {
    Matrix3::from_row_slice(params.as_slice())
}

/// The stacked residuals: predicted minus measured up direction after each turn.
fn residuals(turns: &[Turn], params: &DVector<f64>) -> DVector<f64> {
    let g = matrix_of(params);
    let rows = turns.iter().flat_map(|turn| (rotate_up(turn, &g) - Vector3::from(turn.up_after)).data.0[0]);
    DVector::from_iterator(3 * turns.len(), rows)
}

/// The Jacobian of [`residuals`] by forward differences from `at`, the residuals at `params`.
fn jacobian(turns: &[Turn], params: &DVector<f64>, at: &DVector<f64>) -> DMatrix<f64> {
    let mut j = DMatrix::zeros(3 * turns.len(), params.len());
    for p in 0..params.len() {
        let mut moved = params.clone();
        moved[p] += DIFFERENCE_STEP;
        j.set_column(p, &((residuals(turns, &moved) - at) / DIFFERENCE_STEP));
    }
    j
}

/// One Gauss-Newton step, or `None` when the normal equations are singular.
fn gauss_newton_step(turns: &[Turn], params: &DVector<f64>) -> Option<DVector<f64>> {
    let r = residuals(turns, params);
    let j = jacobian(turns, params, &r);
    (j.transpose() * &j).cholesky().map(|c| c.solve(&(-(j.transpose() * r))))
}

/// The fit with its standard errors: each turn gives two independent constraints (the predicted
/// up is a unit vector), so the residual variance is the sum of squares over 2n - 9.
fn summarise(turns: &[Turn], params: &DVector<f64>) -> Result<GyroFit, GyroFitError> {
    let r = residuals(turns, params);
    let j = jacobian(turns, params, &r);
    let dof = mutant!("gyro-dof-3n", 2 * turns.len(), 3 * turns.len()).saturating_sub(9).max(1) as f64;
    let variance = r.norm_squared() / dof;
    let covariance = (j.transpose() * &j).try_inverse().ok_or(GyroFitError::Diverged)? * variance;
    let g = matrix_of(params);
    let std_errors: Mat3<f64> = [0, 1, 2].map(|i| [0, 1, 2].map(|k| covariance[(3 * i + k, 3 * i + k)].sqrt()));
    let residual_deg = (r.norm_squared() / turns.len() as f64).sqrt().to_degrees();
    Ok(GyroFit {
        matrix: [0, 1, 2].map(|i| [0, 1, 2].map(|k| g[(i, k)])),
        std_errors,
        residual_deg,
        turns: turns.len(),
    })
}
