//! Whether the rows can determine a least-squares model, judged before fitting: the positions'
//! spread over the axes, the known orientations `reference-norm12` needs, and the Jacobian's
//! conditioning at the start.

use nalgebra::allocator::Allocator;
use nalgebra::{Const, DefaultAllocator, DimDiff, DimSub, Matrix3, SMatrix, Vector3, U1};

use super::covariance::inverse_factor;
use super::linearised::Observation;
use super::linearised::{Gram, Linearised, RowsTransposed};
use super::normalization::Normalization;
use super::shape::parameter_name;
use super::shape::Shape;
use super::{FitError, Model};
use crate::data::Dataset;
use crate::limits::POORLY_CONDITIONED_RATIO;
use crate::limits::UNOBSERVABLE_RATIO;
use crate::limits::{AXIS_SPREAD, INDEPENDENT_REFERENCES_DEG};

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

/// Refuses parameters the positions cannot determine, from the column-scaled Jacobian at `start`;
/// warns when the condition number is poor.
pub(super) fn check_conditioning(
    model: Model,
    shape: Shape,
    observations: &[Observation],
    start: &[f64],
    warnings: &mut Vec<String>,
) -> Result<(), FitError> {
    match shape {
        Shape::Diagonal => check_normal(model, shape, &normal_at::<6>(shape, observations, start), warnings),
        Shape::TriangularTimesDiagonal => {
            check_normal(model, shape, &normal_at::<9>(shape, observations, start), warnings)
        }
        Shape::Full => check_normal(model, shape, &normal_at::<12>(shape, observations, start), warnings),
    }
}

/// [`check_conditioning`] from J^T J at the start, `normal`, where the solver has built it.
pub(super) fn check_normal<const P: usize>(
    model: Model,
    shape: Shape,
    normal: &SMatrix<f64, P, P>,
    warnings: &mut Vec<String>,
) -> Result<(), FitError>
where
    Const<P>: DimSub<U1>,
    DefaultAllocator: Allocator<DimDiff<Const<P>, U1>>,
{
    let Some((ratio, weakest)) = poor_conditioning(shape, &column_scaled(normal)) else {
        return Ok(());
    };
    if ratio < UNOBSERVABLE_RATIO {
        return Err(FitError::Unobservable { model: model.name(), parameter: weakest.to_owned() });
    }
    warnings.push(format!(
        "poor condition number {:.1e}: the positions barely determine {weakest}; add positions spread over the sphere",
        1.0 / ratio
    ));
    Ok(())
}

/// Where the ratio of smallest to largest singular value of the column-scaled Jacobian is below
/// [`POORLY_CONDITIONED_RATIO`]: the ratio, and the parameter the smallest one weighs most; `scaled`
/// its normal matrix.
///
/// NOTE: the singular values of the column-scaled Jacobian are the square roots of the eigenvalues
/// of its small normal matrix, which is much cheaper to decompose than J itself.
fn poor_conditioning<const P: usize>(shape: Shape, scaled: &SMatrix<f64, P, P>) -> Option<(f64, &'static str)>
where
    Const<P>: DimSub<U1>,
    DefaultAllocator: Allocator<DimDiff<Const<P>, U1>>,
{
    if surely_conditioned(scaled) {
        return None;
    }
    let eigen = scaled.symmetric_eigen();
    let (largest, smallest) = (eigen.eigenvalues.max().max(0.0).sqrt(), eigen.eigenvalues.min().max(0.0).sqrt());
    let ratio = if largest > 0.0 { smallest / largest } else { 0.0 };
    let (index, _) = eigen.eigenvalues.argmin();
    (ratio < POORLY_CONDITIONED_RATIO).then(|| (ratio, parameter_name(shape, eigen.eigenvectors.column(index).iamax())))
}

/// Whether the symmetric matrix `a` is positive definite with its smallest eigenvalue surely at least
/// [`POORLY_CONDITIONED_RATIO`]^2 times its largest, from one Cholesky factor (an eigen
/// decomposition costs ten of them); `false` says only that the eigenvalues must decide.
///
/// NOTE: the largest eigenvalue is at most trace(A), and the smallest at least 1 / trace(A^-1) (the
/// largest eigenvalue of A^-1 is at most the sum of them all); their ratio is at least
/// 1 / (trace(A) trace(A^-1)). The 1 % margin keeps the bound's rounding from deciding.
pub(super) fn surely_conditioned<const P: usize>(a: &SMatrix<f64, P, P>) -> bool {
    let Some(cholesky) = a.cholesky() else {
        return false;
    };
    // NOTE: trace(A^-1) = trace(L^-T L^-1), the sum of L^-1's squared entries.
    let bound = 1.0 / (a.trace() * inverse_factor(&cholesky.unpack()).norm_squared());
    bound.is_finite() && bound >= POORLY_CONDITIONED_RATIO.powi(2) * 1.01
}

/// J^T J at `start`, in one pass over the rows.
fn normal_at<const P: usize>(shape: Shape, observations: &[Observation], start: &[f64]) -> SMatrix<f64, P, P> {
    let at = Linearised::new(shape, start);
    let (mut normal, mut rows) = (Gram::<P>::new(), RowsTransposed::<P>::zeros());
    for observation in observations {
        let at_row = at.rows(observation, &mut rows);
        normal.push((&rows, at_row.count), &Matrix3::identity());
    }
    normal.matrix()
}

/// `normal` (J^T J) with J's columns scaled to unit length (a zero column stays zero).
fn column_scaled<const P: usize>(normal: &SMatrix<f64, P, P>) -> SMatrix<f64, P, P> {
    let lengths = normal.diagonal().map(|v| if v > 0.0 { v.sqrt() } else { 1.0 });
    SMatrix::from_fn(|i, j| normal[(i, j)] / (lengths[i] * lengths[j]))
}

#[cfg(test)]
mod tests {
    use nalgebra::{Rotation3, SMatrix, Vector3};

    use super::*;

    /// Q diag(eigenvalues) Q^T with Q rotating each consecutive pair of axes.
    fn with_eigenvalues(eigenvalues: [f64; 6]) -> SMatrix<f64, 6, 6> {
        let rotation = Rotation3::from_scaled_axis(Vector3::new(0.4, -0.7, 1.1)).into_inner();
        let mut q = SMatrix::<f64, 6, 6>::zeros();
        q.fixed_view_mut::<3, 3>(0, 0).copy_from(&rotation);
        q.fixed_view_mut::<3, 3>(3, 3).copy_from(&rotation.transpose());
        q * SMatrix::from_diagonal(&eigenvalues.into()) * q.transpose()
    }

    #[test]
    fn the_screen_passes_only_matrices_whose_eigenvalues_would_pass() {
        let threshold = POORLY_CONDITIONED_RATIO.powi(2);
        // NOTE: largest eigenvalue 5, so a screen that took it for 1 would pass a ratio of 0.98e-6.
        let cases = [(1.0, true), (1e-2, true), (1e-4, true), (1.02 * threshold, false), (0.98 * threshold, false)];
        for (ratio, passes) in cases {
            let a = with_eigenvalues([5.0, 5.0, 2.0, 5.0, 5.0 * ratio, 5.0]);
            let eigenvalues = a.symmetric_eigenvalues();
            assert_eq!((eigenvalues.min() / eigenvalues.max() >= threshold), ratio >= threshold, "ratio {ratio}");
            assert_eq!(surely_conditioned(&a), passes, "ratio {ratio}");
        }
        assert!(!surely_conditioned(&with_eigenvalues([1.0, 1.0, 1.0, 1.0, 0.0, 1.0])), "a singular matrix");
    }
}
