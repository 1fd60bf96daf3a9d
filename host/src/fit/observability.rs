//! Whether the rows can determine a least-squares model, judged before fitting: the positions'
//! spread over the axes, the known orientations `reference-norm12` needs, and the Jacobian's
//! conditioning at the start.

use nalgebra::{DMatrix, DVector, Vector3};

use super::models::parameter_name;
use super::nonlinear::{Observation, Problem};
use super::normalization::Normalization;
use super::shape::Shape;
use super::{FitError, Model};
use crate::data::Dataset;
use crate::limits::POORLY_CONDITIONED_RATIO;
use crate::limits::UNOBSERVABLE_RATIO;
use crate::limits::{AXIS_SPREAD, INDEPENDENT_REFERENCES_DEG};
use levenberg_marquardt::LeastSquaresProblem;

/// Known orientations `reference-norm12` needs at least [`INDEPENDENT_REFERENCES_DEG`] apart: two fix
/// the rotation that the |a| = g rows cannot see.
const INDEPENDENT_REFERENCES: usize = 2;

/// Refuses, before fitting, positions that cannot determine the model, naming what to add; judged on
/// the normalised readings, so that the file's zero and unit do not matter.
pub(super) fn check_positions(
    training: &Dataset,
    model: Model,
    shape: Shape,
    normalization: &Normalization,
) -> Result<(), FitError> {
    if model == Model::ReferenceNorm12 {
        return check_references(training, model, shape);
    }
    let needed = shape.len() + 3;
    if training.rows.len() < needed {
        return Err(FitError::TooFewPositions { model: model.name(), needed, found: training.rows.len() });
    }
    for (axis, letter) in ['x', 'y', 'z'].into_iter().enumerate() {
        for up in [true, false] {
            if !points_along(training, normalization, axis, up) {
                return Err(FitError::NoSpread { model: model.name(), axis: letter, up });
            }
        }
    }
    Ok(())
}

/// `reference-norm12` needs two independent known orientations and one residual per parameter.
fn check_references(training: &Dataset, model: Model, shape: Shape) -> Result<(), FitError> {
    let name = model.name();
    let references: Vec<[f64; 3]> = training.rows.iter().filter_map(|r| r.reference).collect();
    if independent_pair(&references).is_none() {
        return Err(FitError::TooFewReferences {
            model: name,
            needed: INDEPENDENT_REFERENCES,
            found: references.len().min(1),
        });
    }
    let residuals = training.rows.len() + 2 * references.len();
    if residuals < shape.len() + 3 {
        let needed = training.rows.len() + shape.len() + 3 - residuals;
        return Err(FitError::TooFewPositions { model: name, needed, found: training.rows.len() });
    }
    Ok(())
}

/// The first two known orientations more than [`INDEPENDENT_REFERENCES_DEG`] apart (their indices).
pub(super) fn independent_pair(references: &[[f64; 3]]) -> Option<(usize, usize)> {
    let apart = |(i, a): (usize, &[f64; 3])| {
        references.iter().position(|b| angle_between(a, b) > INDEPENDENT_REFERENCES_DEG).map(|j| (i, j))
    };
    references.iter().enumerate().find_map(apart)
}

/// Whether some normalised reading points `axis` up (or down) within the spread the fits need.
fn points_along(training: &Dataset, normalization: &Normalization, axis: usize, up: bool) -> bool {
    training.rows.iter().any(|r| reading_points_along(normalization.apply(r.reading), axis, up))
}

/// Whether one normalised reading points `axis` up (or down) within the spread the fits need.
pub(super) fn reading_points_along(m: Vector3<f64>, axis: usize, up: bool) -> bool {
    let sign = if up { 1.0 } else { -1.0 };
    sign * m[axis] > AXIS_SPREAD * m.norm()
}

fn angle_between(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    shared::orientation::angle_between_deg(*a, *b)
}

/// Refuses parameters the positions cannot determine, from the column-scaled Jacobian at the start;
/// warns when the condition number is poor.
pub(super) fn check_conditioning(
    model: Model,
    shape: Shape,
    observations: &[Observation],
    start: &DVector<f64>,
    warnings: &mut Vec<String>,
) -> Result<(), FitError> {
    let jacobian = Problem::new(shape, observations, start.clone()).jacobian().ok_or(FitError::Degenerate)?;
    let (ratio, weakest) = conditioning(shape, &jacobian);
    if ratio < UNOBSERVABLE_RATIO {
        return Err(FitError::Unobservable { model: model.name(), parameter: weakest });
    }
    if ratio < POORLY_CONDITIONED_RATIO {
        warnings.push(format!(
            "poor condition number {:.1e}: the positions barely determine {weakest}; add positions spread over the sphere",
            1.0 / ratio
        ));
    }
    Ok(())
}

/// The ratio of smallest to largest singular value of the column-scaled Jacobian, and the parameter
/// the smallest one weighs most.
fn conditioning(shape: Shape, jacobian: &DMatrix<f64>) -> (f64, String) {
    // NOTE: the singular values of the column-scaled Jacobian are the square roots of the
    // eigenvalues of its small normal matrix, which is much cheaper to decompose than J itself.
    let scaled = column_scaled(jacobian);
    let eigen = (scaled.transpose() * &scaled).symmetric_eigen();
    let (largest, smallest) = (eigen.eigenvalues.max().max(0.0).sqrt(), eigen.eigenvalues.min().max(0.0).sqrt());
    let ratio = if largest > 0.0 { smallest / largest } else { 0.0 };
    let (index, _) = eigen.eigenvalues.argmin();
    (ratio, parameter_name(shape, eigen.eigenvectors.column(index).iamax()))
}

fn column_scaled(jacobian: &DMatrix<f64>) -> DMatrix<f64> {
    let mut scaled = jacobian.clone();
    for mut column in scaled.column_iter_mut() {
        let norm = column.norm();
        if norm > 0.0 {
            column /= norm;
        }
    }
    scaled
}
