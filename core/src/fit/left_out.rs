//! Leave-one-out in about the time of one fit: each row's figure comes from the fit to all rows and
//! the row's influence on it (host `fit/influence.rs`: exact for `linear12`, the Gauss-Newton step
//! for the nonlinear models), and only the few rows the fit hangs on are refitted without them.
//! Refitting every row made `fit` quadratic in rows (10 000 rows: 10 000 fits).

use nalgebra::{DMatrix, Vector3};
use shared::linalg;

use super::influence::Influence;
use super::linear::{self, Pair, MIN_REFERENCES};
use super::linearised::Observation;
use super::models::{self, Solved};
use super::nonlinear::Problem;
use super::normalization::Normalization;
use super::observability::{independent_pair, reading_points_along};
use super::shape::Shape;
use super::{fit_model, uncertainty, Fit, FitError, FitOptions, Model};
use crate::data::Dataset;
use crate::limits::HIGH_LEVERAGE;
use levenberg_marquardt::LeastSquaresProblem;

/// One row's leave-one-out figure, or the need to refit without it.
enum LeftOut {
    /// | |a| - g | at the row from the fit without it, in output units.
    Error(f64),
    /// The row carries the fit (a check could refuse the rest, or its leverage is high): refit.
    Refit,
}

/// RMS over the rows of | |a| - g | at each row, from the model fitted without it; `None` when the
/// model cannot be fitted with some row left out.
pub fn leave_one_out_rms(training: &Dataset, model: Model, options: &FitOptions) -> Option<f64> {
    let rows = left_out_rows(training, model, options).ok()?;
    let mut sum = 0.0;
    for (index, row) in rows.into_iter().enumerate() {
        let error = match row {
            LeftOut::Error(error) => error,
            LeftOut::Refit => refit_error(training, index, model, options)?,
        };
        sum += error * error;
    }
    (!training.rows.is_empty()).then(|| (sum / training.rows.len() as f64).sqrt())
}

/// Each row's figure from the fit of all rows, or the need to refit without it.
fn left_out_rows(training: &Dataset, model: Model, options: &FitOptions) -> Result<Vec<LeftOut>, FitError> {
    match model {
        Model::SixPosition => six_position(training, options),
        Model::Linear12 => linear12(training, options),
        Model::ReferenceNorm12 | Model::Ortho9 | Model::Diag6 => least_squares(training, model, options),
    }
}

/// | |a| - g | at row `index` from the model refitted without it; `None` when the refit is refused.
fn refit_error(training: &Dataset, index: usize, model: Model, options: &FitOptions) -> Option<f64> {
    let mut without = training.clone();
    let row = without.rows.remove(index);
    let fit = fit_model(&without, model, options).ok()?;
    Some(norm_error(&fit.matrix, &fit.offset, row.reading, options.g))
}

/// | |M (m - o)| - g |.
fn norm_error(matrix: &linalg::Mat3<f64>, offset: &linalg::Vec3<f64>, reading: [f64; 3], g: f64) -> f64 {
    (linalg::norm(linalg::mul_vec(matrix, linalg::sub(reading, *offset))) - g).abs()
}

/// The rows' own errors under `fit` (rows it does not use: leaving them out changes nothing).
fn own_errors(training: &Dataset, fit: &Fit, g: f64) -> Vec<LeftOut> {
    training.rows.iter().map(|r| LeftOut::Error(norm_error(&fit.matrix, &fit.offset, r.reading, g))).collect()
}

/// The closed form uses one reading per face, and each is needed: those are refitted (and refused).
fn six_position(training: &Dataset, options: &FitOptions) -> Result<Vec<LeftOut>, FitError> {
    let fit = fit_model(training, Model::SixPosition, options)?;
    let mut rows = own_errors(training, &fit, options.g);
    for (row, left_out) in training.rows.iter().zip(&mut rows) {
        if fit.lines_used.contains(&row.line) {
            *left_out = LeftOut::Refit;
        }
    }
    Ok(rows)
}

/// `linear12` is linear in (X, y) of m = X a + y: the influence gives each refit exactly.
fn linear12(training: &Dataset, options: &FitOptions) -> Result<Vec<LeftOut>, FitError> {
    let fit = fit_model(training, Model::Linear12, options)?;
    let pairs = linear::reference_pairs(training);
    let per_sample = uncertainty::pooled_sample_variance(training);
    let roots: Vec<f64> = linear::pair_weights(&pairs, Model::Linear12, per_sample).iter().map(|w| w.sqrt()).collect();
    let sensor = linalg::inverse(&fit.matrix).ok_or(FitError::Degenerate)?;
    // NOTE: per reading axis k, (X row k, y_k) in column k; the residual m - X a - y has the Jacobian
    // -[a 1] in it, the same for the three axes.
    let coefficients = DMatrix::from_fn(4, 3, |j, k| if j < 3 { sensor[k][j] } else { fit.offset[k] });
    let design = |p: &Pair, j: usize| if j < 3 { p.reference[j] } else { 1.0 };
    let jacobian = DMatrix::from_fn(pairs.len(), 4, |i, j| -roots[i] * design(&pairs[i], j));
    let influence = Influence::new(&jacobian).ok_or(FitError::Degenerate)?;
    let mut rows = own_errors(training, &fit, options.g);
    for (i, pair) in pairs.iter().enumerate() {
        let predicted = linalg::add(linalg::mul_vec(&sensor, pair.reference), fit.offset);
        let residual = DMatrix::from_fn(1, 3, |_, k| roots[i] * (pair.reading[k] - predicted[k]));
        let removal = influence.removal(&jacobian.rows(i, 1).into_owned(), &residual);
        let kept = removal.filter(|r| pairs.len() > MIN_REFERENCES && r.leverage <= HIGH_LEVERAGE);
        let error = kept.and_then(|r| linear12_error(&(&coefficients + r.step), pair.reading, options.g));
        rows[pair.row] = error.map_or(LeftOut::Refit, LeftOut::Error);
    }
    Ok(rows)
}

/// | |a| - g | at `reading` under the coefficients (X, y) of m = X a + y.
fn linear12_error(coefficients: &DMatrix<f64>, reading: [f64; 3], g: f64) -> Option<f64> {
    let sensor = [0, 1, 2].map(|k| [0, 1, 2].map(|j| coefficients[(j, k)]));
    let offset = [0, 1, 2].map(|k| coefficients[(3, k)]);
    Some(norm_error(&linalg::inverse(&sensor)?, &offset, reading, g))
}

/// The nonlinear models: each row's Gauss-Newton step from the solution of all rows.
fn least_squares(training: &Dataset, model: Model, options: &FitOptions) -> Result<Vec<LeftOut>, FitError> {
    let solved = models::solved(training, model, options)?;
    let problem = Problem::new(solved.shape, &solved.observations, solved.solution.params.clone());
    let (jacobian, residuals) = problem.jacobian().zip(problem.residuals()).ok_or(FitError::Degenerate)?;
    let influence = Influence::new(&jacobian).ok_or(FitError::Degenerate)?;
    let hangs = rows_the_checks_hang_on(training, model, solved.shape, &solved.normalization);
    let mut first = 0;
    let mut rows = Vec::with_capacity(training.rows.len());
    for (observation, hangs) in solved.observations.iter().zip(hangs) {
        let count = if observation.reference.is_some() { 3 } else { 1 };
        let row_jacobian = jacobian.rows(first, count).into_owned();
        let row_residuals = DMatrix::from_column_slice(count, 1, &residuals.as_slice()[first..first + count]);
        first += count;
        let removal =
            influence.removal(&row_jacobian, &row_residuals).filter(|r| !hangs && r.leverage <= HIGH_LEVERAGE);
        rows.push(
            removal.map_or(LeftOut::Refit, |r| LeftOut::Error(solver_error(&solved, &r.step, observation) * options.g)),
        );
    }
    Ok(rows)
}

/// | |a| - 1 | in g at an observation, with the solution's parameters moved by `step`.
fn solver_error(solved: &Solved, step: &DMatrix<f64>, observation: &Observation) -> f64 {
    let params = &solved.solution.params + step.column(0);
    let n = solved.shape.len();
    let matrix = solved.shape.matrix(&params.as_slice()[..n]);
    let offset = Vector3::new(params[n], params[n + 1], params[n + 2]);
    ((matrix * (observation.reading - offset)).norm() - 1.0).abs()
}

/// Rows whose removal the checks before a least-squares fit could refuse (then the refit says so):
/// for `reference-norm12` the two known orientations that make the pair it needs; for the others the
/// rows that alone, or with one other, point an axis up or down (two, not one: leaving a row out
/// moves the normalisation a little); every row when there are barely enough.
fn rows_the_checks_hang_on(training: &Dataset, model: Model, shape: Shape, normalization: &Normalization) -> Vec<bool> {
    let n = training.rows.len();
    let mut hangs = vec![false; n];
    if model == Model::ReferenceNorm12 {
        let references: Vec<(usize, [f64; 3])> =
            training.rows.iter().enumerate().filter_map(|(i, r)| r.reference.map(|v| (i, v))).collect();
        if n + 2 * references.len() < shape.len() + 3 + 3 {
            return vec![true; n];
        }
        let directions: Vec<[f64; 3]> = references.iter().map(|(_, v)| *v).collect();
        for k in independent_pair(&directions).map_or(vec![], |(a, b)| vec![a, b]) {
            hangs[references[k].0] = true;
        }
        return hangs;
    }
    if n <= shape.len() + 3 {
        return vec![true; n];
    }
    let readings: Vec<Vector3<f64>> = training.rows.iter().map(|r| normalization.apply(r.reading)).collect();
    for (axis, up) in (0..3).flat_map(|axis| [(axis, true), (axis, false)]) {
        let along: Vec<usize> = (0..n).filter(|&i| reading_points_along(readings[i], axis, up)).collect();
        if along.len() <= 2 {
            along.into_iter().for_each(|i| hangs[i] = true);
        }
    }
    hangs
}

/// `fit`'s prediction with the misfit its rows show when each is left out (see
/// [`super::Prediction::with_held_out`]); the prediction as it was where no row can be left out.
pub fn with_misfit(fit: &Fit, training: &Dataset, options: &FitOptions) -> Option<super::Prediction> {
    let prediction = fit.prediction?;
    let chosen =
        fit.selection.as_ref().and_then(|s| s.leave_one_out.iter().find(|(name, _)| *name == fit.model.name()));
    let held_out = match chosen {
        Some((_, figure)) => *figure,
        None => leave_one_out_rms(training, fit.model, options),
    };
    let mg = |value: f64| value / options.g * 1000.0;
    Some(match held_out {
        Some(held_out) => prediction.with_held_out(mg(held_out), mg(row_noise(training))),
        None => prediction,
    })
}

/// The RMS noise of a row's mean along any one axis, in output units, from the rows' `count` and
/// `std`; 0 where the rows do not carry them (the held-out error is then all taken as misfit).
fn row_noise(training: &Dataset) -> f64 {
    let variances: Vec<f64> = training
        .rows
        .iter()
        .filter_map(|row| Some(row.std?.iter().map(|s| s * s).sum::<f64>() / 3.0 / f64::from(row.count?.max(1))))
        .collect();
    match variances.len() == training.rows.len() && !variances.is_empty() {
        true => (variances.iter().sum::<f64>() / variances.len() as f64).sqrt(),
        false => 0.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::synthetic::random_positions;

    /// How many rows leave-one-out refits for `model`; the rest take one fit's influence.
    fn refits(training: &Dataset, model: Model) -> usize {
        let rows = left_out_rows(training, model, &FitOptions::default()).unwrap();
        rows.iter().filter(|row| matches!(row, LeftOut::Refit)).count()
    }

    #[test]
    fn leave_one_out_refits_only_the_rows_the_fit_hangs_on_however_many_rows_there_are() {
        for positions in [200, 2000] {
            let (with, without) =
                (random_positions(7, positions, 1e-4, true), random_positions(7, positions, 1e-4, false));
            let counted = [
                refits(&with, Model::Linear12),
                refits(&with, Model::ReferenceNorm12),
                refits(&without, Model::Ortho9),
                refits(&without, Model::Diag6),
            ];
            println!("{positions} rows: refitted {counted:?} (linear12, reference-norm12, ortho9, diag6)");
            // NOTE: at most two rows per axis direction (up, down) pointing along it, or the pair
            // reference-norm12 needs; high leverage does not occur among hundreds of rows.
            assert!(counted.iter().all(|&n| n <= 12), "{positions} rows: {counted:?}");
        }
    }
}
