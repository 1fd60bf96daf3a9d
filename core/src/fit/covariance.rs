//! A least-squares fit's statistics from one pass over its rows at the solution, on fixed-size
//! matrices (P parameters): J^T J, the residuals' chi-square against the pooled noise (with the middle
//! of the noise's sandwich) and against each row's own noise (the noise test); then both parameter
//! covariances from the one Cholesky factor of J^T J.

use nalgebra::{Matrix3, SMatrix, Vector3};

use super::linearised::Observation;
use super::linearised::{Gram, Linearised, RowsAt, RowsTransposed};
use super::nonlinear::Solution;
use super::normalization::Normalization;
use super::shape::Shape;
use super::{statistics, uncertainty};
use crate::data::{Dataset, Row};

/// A P x P matrix.
pub(super) type Square<const P: usize> = SMatrix<f64, P, P>;

/// What the statistics need from the rows at the solution, gathered in one pass.
pub(super) struct Accumulated<const P: usize> {
    /// J^T J.
    pub normal: Square<P>,
    /// Number of residuals.
    pub residuals: usize,
    /// sum J_i^T V_i J_i and sum r_i^T V_i^-1 r_i, V_i the covariance of row i's residuals from the
    /// pooled sample noise; `None` without it (or where a V_i is not positive definite).
    pub pooled: Option<(Square<P>, f64)>,
    /// sum of r_i^2 / var(r_i) from each row's own noise; `None` unless every row states it.
    pub own: Option<f64>,
}

/// One pass over the rows at the solution.
pub(super) fn accumulate<const P: usize>(
    training: &Dataset,
    shape: Shape,
    solution: &Solution,
    observations: &[Observation],
    normalization: &Normalization,
) -> Accumulated<P> {
    let at = Linearised::new(shape, solution.params.as_slice());
    let pooled = uncertainty::pooled_sample_variance(training);
    let per_sample = pooled.map(|v| Vector3::from_fn(|k, _| v[k] / normalization.radii[k].powi(2)));
    let (mut normal, mut sandwich) = (Gram::<P>::new(), per_sample.map(|_| Gram::<P>::new()));
    let (mut residuals, mut pooled_chi_square, mut own) = (0, Some(0.0), Some(0.0));
    let mut transposed = RowsTransposed::<P>::zeros();
    for (row, observation) in training.rows.iter().zip(observations) {
        let rows = at.rows(observation, &mut transposed);
        normal.push((&transposed, rows.count), &Matrix3::identity());
        residuals += rows.count;
        pooled_chi_square = pooled_chi_square.zip(per_sample).and_then(|(sum, noise)| {
            let reading = noise / f64::from(row.count?) * observation.weight.powi(2);
            let (scale, term) = pooled_term(&rows, &reading, &at.matrix)?;
            sandwich.as_mut()?.push((&transposed, rows.count), &scale);
            Some(sum + term)
        });
        own = own.and_then(|sum| Some(sum + own_term(row, &rows, &at.matrix, normalization, observation.weight)?));
    }
    let pooled = sandwich.zip(pooled_chi_square).map(|(s, chi_square)| (s.matrix(), chi_square));
    Accumulated { normal: normal.matrix(), residuals, pooled, own }
}

/// One row's V_i (the covariance of its residuals from the pooled noise; its [0][0] for a norm row)
/// and its share r^T V_i^-1 r of chi-square: `reading` the variances of its normalised reading per
/// axis, already scaled by the row's weight squared. `None` where V_i is not positive definite.
fn pooled_term(rows: &RowsAt, reading: &Vector3<f64>, matrix: &Matrix3<f64>) -> Option<(Matrix3<f64>, f64)> {
    match rows.along {
        None => {
            let full = matrix * Matrix3::from_diagonal(reading) * matrix.transpose();
            let term = (rows.residuals.transpose() * full.cholesky()?.inverse() * rows.residuals)[0];
            Some((full, term))
        }
        Some(along) => {
            let variance = statistics::variance_along(&along, reading);
            // NOTE: not positive (or NaN): no variance, as a Cholesky factor would refuse it.
            (variance > 0.0).then(|| (Matrix3::from_diagonal_element(variance), rows.residuals[0].powi(2) / variance))
        }
    }
}

/// One row's share of the noise test's chi-square, from the noise it states itself; `weight` the
/// row's weight in the fit, which its residuals carry.
fn own_term(
    row: &Row,
    rows: &RowsAt,
    matrix: &Matrix3<f64>,
    normalization: &Normalization,
    weight: f64,
) -> Option<f64> {
    // NOTE: the weighted residual w r has variance w^2 var(r): dividing it by var(r) alone counted
    // a row of twice the mean count four times over (issue 29).
    let variances = statistics::normalised_variance_of_mean(row, normalization)? * weight.powi(2);
    Some(statistics::chi_square_term(&rows.residuals, rows.along, matrix, &variances))
}

/// The covariances behind the standard errors, in the solver's units, from one Cholesky factor of
/// J^T J: the scatter's s^2 (J^T J)^-1 (with redundancy), and the pooled noise's sandwich
/// (J^T J)^-1 J^T V J (J^T J)^-1 with its chi-square.
pub(super) fn covariances<const P: usize>(
    sums: &Accumulated<P>,
    cost: f64,
) -> (Option<Square<P>>, Option<(Square<P>, f64)>) {
    let Some(inverse) = sums.normal.cholesky().map(|c| inverse_of_factor(&c.unpack())) else {
        return (None, None);
    };
    let degrees_of_freedom = sums.residuals.checked_sub(P).filter(|&d| d > 0);
    let scatter = degrees_of_freedom.map(|d| inverse * (cost / d as f64));
    let noise = sums.pooled.map(|(middle, chi_square)| (inverse * middle * inverse, chi_square));
    (scatter, noise)
}

/// L^-1 of a lower-triangular L (the Cholesky factor of A = L L^T, whose inverse is L^-T L^-1), by
/// forward substitution.
///
/// NOTE: on fixed sizes, not by nalgebra's `Cholesky::inverse`: its substitutions run on dynamic
/// views and took about 0.7 us for a 9x9 matrix, a tenth of the whole fit, against well under a
/// tenth of that here.
pub(super) fn inverse_factor<const P: usize>(factor: &Square<P>) -> Square<P> {
    let mut inverse = Square::<P>::zeros();
    for j in 0..P {
        inverse[(j, j)] = 1.0 / factor[(j, j)];
        for i in j + 1..P {
            let sum: f64 = (j..i).map(|k| factor[(i, k)] * inverse[(k, j)]).sum();
            inverse[(i, j)] = -sum / factor[(i, i)];
        }
    }
    inverse
}

/// A^-1 from its Cholesky factor L: L^-T L^-1.
fn inverse_of_factor<const P: usize>(factor: &Square<P>) -> Square<P> {
    let inverse = inverse_factor(factor);
    inverse.tr_mul(&inverse)
}

#[cfg(test)]
mod tests {
    use levenberg_marquardt::LeastSquaresProblem;
    use nalgebra::DMatrix;

    use super::*;
    use crate::fit::models::solved;
    use crate::fit::nonlinear::Problem;
    use crate::fit::{FitOptions, Model};
    use crate::sim::synthetic::random_positions;

    /// 24 rows of 2 to 2231 samples (so the rows weigh differently), with their noise.
    fn problem(seed: u64, references: bool) -> Dataset {
        let mut data = random_positions(seed, 24, 1e-4, references);
        for (i, row) in data.rows.iter_mut().enumerate() {
            let count = 2 + 97 * i as u32;
            row.count = Some(count);
            row.std = Some([1e-4, 1.3e-4, 0.8e-4].map(|s| s * f64::from(count).sqrt()));
        }
        data
    }

    /// The same covariances written out on dynamic matrices: J from the solver's interface, V block
    /// by block, every inverse by LU instead of the one Cholesky factor the fit reuses.
    fn independent(data: &Dataset, model: Model) -> (DMatrix<f64>, DMatrix<f64>, f64) {
        let solved = solved(data, model, &FitOptions::default()).unwrap();
        let problem = Problem::new(solved.shape, &solved.observations, solved.solution.params.clone());
        let (jacobian, residuals) = (problem.jacobian().unwrap(), problem.residuals().unwrap());
        let at = Linearised::new(solved.shape, solved.solution.params.as_slice());
        let pooled = uncertainty::pooled_sample_variance(data).unwrap();
        let mut v = DMatrix::zeros(residuals.len(), residuals.len());
        let mut first = 0;
        for (row, observation) in data.rows.iter().zip(&solved.observations) {
            let reading = Matrix3::from_fn(|i, j| {
                if i == j {
                    pooled[i] / solved.normalization.radii[i].powi(2) / f64::from(row.count.unwrap())
                } else {
                    0.0
                }
            });
            let block = at.matrix * reading * at.matrix.transpose() * observation.weight.powi(2);
            if observation.reference.is_some() {
                v.view_mut((first, first), (3, 3)).copy_from(&block);
                first += 3;
            } else {
                let a = at.matrix * (observation.reading - at.offset);
                v[(first, first)] = (a.transpose() * block * a)[0] / a.norm_squared();
                first += 1;
            }
        }
        let inverse = (jacobian.transpose() * &jacobian).try_inverse().unwrap();
        let dof = (residuals.len() - jacobian.ncols()) as f64;
        let scatter = &inverse * (residuals.norm_squared() / dof);
        let noise = &inverse * jacobian.transpose() * &v * &jacobian * &inverse;
        let chi_square = (residuals.transpose() * v.try_inverse().unwrap() * &residuals)[0];
        (scatter, noise, chi_square)
    }

    /// The largest difference between two covariances, each entry relative to sqrt(C_ii C_jj).
    fn worst<const P: usize>(ours: &Square<P>, theirs: &DMatrix<f64>) -> f64 {
        let scale = |i: usize, j: usize| (theirs[(i, i)] * theirs[(j, j)]).sqrt();
        (0..P * P)
            .map(|k| (k / P, k % P))
            .map(|(i, j)| (ours[(i, j)] - theirs[(i, j)]).abs() / scale(i, j))
            .fold(0.0, f64::max)
    }

    fn check<const P: usize>(model: Model, references: bool) {
        for seed in 0..10 {
            let data = problem(40 + seed, references);
            let solved = solved(&data, model, &FitOptions::default()).unwrap();
            let sums =
                accumulate::<P>(&data, solved.shape, &solved.solution, &solved.observations, &solved.normalization);
            let (scatter, noise) = covariances(&sums, solved.solution.cost);
            let ((scatter, (noise, chi_square)), expected) = (scatter.zip(noise).unwrap(), independent(&data, model));
            let errors =
                [worst(&scatter, &expected.0), worst(&noise, &expected.1), (chi_square / expected.2 - 1.0).abs()];
            assert!(errors.iter().all(|&e| e < 1e-12), "{} seed {seed}: {errors:?}", model.name());
        }
    }

    /// The noise test's chi-square written out: each row's unweighted residual (|a| - 1, or a - ref
    /// per axis) squared over its variance from the noise the row states, sigma^2 / count per axis.
    fn own_chi_square<const P: usize>(data: &Dataset, model: Model) -> (f64, f64) {
        let solved = solved(data, model, &FitOptions::default()).unwrap();
        let at = Linearised::new(solved.shape, solved.solution.params.as_slice());
        let term = |(row, observation): (&Row, &Observation)| {
            let a = at.matrix * (observation.reading - at.offset);
            let (count, std, radii) = (f64::from(row.count.unwrap()), row.std.unwrap(), solved.normalization.radii);
            let variance = Vector3::from_fn(|k, _| (std[k] / count.sqrt() / radii[k]).powi(2));
            let covariance = at.matrix * Matrix3::from_diagonal(&variance) * at.matrix.transpose();
            match observation.reference {
                Some(reference) => (0..3).map(|k| (a - reference)[k].powi(2) / covariance[(k, k)]).sum(),
                None => (a.norm() - 1.0).powi(2) / (a.normalize().transpose() * covariance * a.normalize())[0],
            }
        };
        let expected = data.rows.iter().zip(&solved.observations).map(term).sum();
        let sums = accumulate::<P>(data, solved.shape, &solved.solution, &solved.observations, &solved.normalization);
        (sums.own.unwrap(), expected)
    }

    #[test]
    fn the_noise_test_divides_each_rows_own_residual_by_its_own_variance_when_the_rows_weigh_differently() {
        for seed in 0..5 {
            let norm_rows = own_chi_square::<9>(&problem(60 + seed, false), Model::Ortho9);
            let reference_rows = own_chi_square::<12>(&problem(60 + seed, true), Model::ReferenceNorm12);
            for (ours, expected) in [norm_rows, reference_rows] {
                assert!((ours / expected - 1.0).abs() < 1e-12, "seed {seed}: {ours} vs {expected}");
            }
        }
    }

    #[test]
    fn covariances_from_the_one_reused_factor_equal_independent_inverses_to_1e_12() {
        check::<6>(Model::Diag6, false);
        check::<9>(Model::Ortho9, false);
        check::<12>(Model::ReferenceNorm12, true);
    }
}
