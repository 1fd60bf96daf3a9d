//! Fitting a temperature model (DESIGN.md, "Conventions for the next capabilities") to averages of
//! the resting board at several temperatures, around a static calibration taken at T_ref.
//!
//! Per accelerometer axis k the reading is m_k = p(dT) + q(dT) u_k, with u_k = (M^-1 f)_k the part of
//! the reading the true specific force f explains at T_ref and p, q polynomials in dT = T - T_ref;
//! then o(T) - o = p(dT) - p(0) and 1 + d(dT) = q(dT) / q(0). With a single orientation u_k does
//! not vary and only p (the offset) is fitted. Per gyro axis, w_k = b_k(dT) + g . f (the
//! g-sensitivity, not a function of T). The polynomial order (1-3) of each axis is the one with the
//! smallest held-out error: the points are split into alternate temperature bins, each half predicts
//! the other; an order is tried only where the span learned supports it (10 degC per order).

use crate::limits::{SCALE_DRIFT_FORCE_G, THERMAL_SPAN_PER_ORDER_C};
use nalgebra::{DMatrix, DVector};
use shared::calibration::{TempCoefficients, TemperatureModel, MAX_TEMP_ORDER};
use shared::linalg::{self, Mat3, Vec3};

/// One averaged reading of the resting board.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ThermalPoint {
    /// Die temperature the sensor reported, in degC.
    pub temp_c: f64,
    /// The true specific force, in g (the face the board rested on).
    pub force_g: Vec3<f64>,
    /// Mean accelerometer reading, in g.
    pub accel_g: Vec3<f64>,
    /// Mean gyro reading, in deg/s.
    pub gyro_dps: Vec3<f64>,
}

/// The static calibration a temperature model is fitted around.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ThermalReference {
    /// T_ref: the temperature the static calibration was taken at, in degC.
    pub ref_temp_c: f32,
    /// Its correction matrix M.
    pub matrix: Mat3<f32>,
}

/// A fitted temperature model and how well it predicts.
#[derive(Debug, Clone, PartialEq)]
pub struct ThermalFit {
    /// The model, around the static calibration's mean temperature.
    pub model: TemperatureModel,
    /// The polynomial order chosen per accelerometer axis.
    pub accel_order: [usize; 3],
    /// The polynomial order chosen per gyro axis.
    pub gyro_order: [usize; 3],
    /// Held-out RMS error of the accelerometer at the chosen orders, in mg.
    pub held_out_mg: f64,
    /// Whether the sensitivity could be fitted (several orientations).
    pub scale_fitted: bool,
}

/// Why no temperature model could be fitted.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum ThermalFitError {
    /// Too few temperatures for a polynomial of order 1 on each half.
    #[error("only {bins} temperature bins were learned; at least 6 are needed")]
    TooFewBins { bins: usize },
    /// The least-squares problem had no unique solution.
    #[error("the temperature fit is degenerate: the readings do not vary enough with temperature")]
    Degenerate,
}

/// The regressors of one accelerometer axis: dT^j (j = 0..=order), and u dT^j when fitting scale.
fn accel_row(dt: f64, u: f64, order: usize, scale: bool) -> Vec<f64> {
    let powers: Vec<f64> = (0..=order).map(|j| dt.powi(j as i32)).collect();
    let scaled = powers.iter().map(|p| p * u).filter(|_| scale);
    powers.iter().copied().chain(scaled).collect()
}

/// The regressors of one gyro axis: dT^j (j = 0..=order), then the specific force (g-sensitivity).
fn gyro_row(dt: f64, force: Vec3<f64>, order: usize) -> Vec<f64> {
    (0..=order).map(|j| dt.powi(j as i32)).chain(force).collect()
}

/// Least squares: the coefficients of `rows` that best give `values`.
fn solve(rows: &[Vec<f64>], values: &[f64]) -> Result<Vec<f64>, ThermalFitError> {
    let width = rows.first().map_or(0, Vec::len);
    let design = DMatrix::from_fn(rows.len(), width, |i, j| rows[i][j]);
    let target = DVector::from_column_slice(values);
    let solution = design.svd(true, true).solve(&target, 1e-12).map_err(|_| ThermalFitError::Degenerate)?;
    Ok(solution.iter().copied().collect())
}

/// RMS of (prediction - value) on the `test` rows of a fit to the `train` rows.
fn held_out_rms(rows: &[Vec<f64>], values: &[f64], train: &[bool]) -> Result<f64, ThermalFitError> {
    let pick = |keep: bool| -> (Vec<Vec<f64>>, Vec<f64>) {
        let chosen = (0..rows.len()).filter(|&i| train[i] == keep);
        chosen.map(|i| (rows[i].clone(), values[i])).unzip()
    };
    let (fit_rows, fit_values) = pick(true);
    let (test_rows, test_values) = pick(false);
    let coefficients = solve(&fit_rows, &fit_values)?;
    let squares: f64 =
        test_rows.iter().zip(&test_values).map(|(r, v)| (dot(r, &coefficients) - v).powi(2)).sum::<f64>();
    Ok((squares / test_values.len().max(1) as f64).sqrt())
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// The highest order the points' temperature span supports (1..=3).
fn highest_order(points: &[ThermalPoint]) -> usize {
    let (low, high) =
        points.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| (l.min(p.temp_c), h.max(p.temp_c)));
    ((high - low) / THERMAL_SPAN_PER_ORDER_C).floor().clamp(1.0, MAX_TEMP_ORDER as f64) as usize
}

/// How a temperature polynomial's order is chosen: by its error on the rows it was not fitted to,
/// the rows split in two folds, orders from 1 up to `highest`.
#[derive(Debug, Clone, Copy)]
struct Folds<'a> {
    /// Whether each row is in the first fold (the others make the second).
    first: &'a [bool],
    /// The highest order tried.
    highest: usize,
}

/// The order (1..=`folds.highest`) with the smallest held-out error, with that error; both folds count.
fn choose_order(build: impl Fn(usize) -> Vec<Vec<f64>>, values: &[f64], folds: Folds) -> (usize, f64) {
    let (fold, highest) = (folds.first, folds.highest);
    let other: Vec<bool> = fold.iter().map(|f| !f).collect();
    let error = |order: usize| {
        let rows = build(order);
        let a = held_out_rms(&rows, values, fold).unwrap_or(f64::INFINITY);
        let b = held_out_rms(&rows, values, &other).unwrap_or(f64::INFINITY);
        ((a * a + b * b) / 2.0).sqrt()
    };
    (1..=highest).map(|order| (order, error(order))).fold(
        (1, f64::INFINITY),
        |best, c| {
            if c.1 < best.1 {
                c
            } else {
                best
            }
        },
    )
}

/// Powers 1..=order of a fitted polynomial, divided by `norm`, as a model's coefficient column.
fn coefficients_into(column: &mut TempCoefficients, axis: usize, polynomial: &[f64], norm: f64) {
    for (k, value) in polynomial.iter().skip(1).enumerate().take(MAX_TEMP_ORDER) {
        column[k][axis] = (value / norm) as f32;
    }
}

/// Fits the temperature model around the static calibration `reference` to `points`.
pub fn fit_temperature(reference: &ThermalReference, points: &[ThermalPoint]) -> Result<ThermalFit, ThermalFitError> {
    let ref_c = f64::from(reference.ref_temp_c);
    let bins: Vec<i64> = points.iter().map(|p| p.temp_c.floor() as i64).collect();
    let distinct = bins.iter().collect::<std::collections::BTreeSet<_>>().len();
    if distinct < 6 {
        return Err(ThermalFitError::TooFewBins { bins: distinct });
    }
    let fold: Vec<bool> = bins.iter().map(|b| b.rem_euclid(2) == 0).collect();
    let folds = Folds { first: &fold, highest: highest_order(points) };
    let sensor = linalg::inverse(&reference.matrix).unwrap_or(linalg::identity());
    let mut fit = ThermalFit {
        model: TemperatureModel::flat(reference.ref_temp_c),
        accel_order: [1; 3],
        gyro_order: [1; 3],
        held_out_mg: 0.0,
        scale_fitted: false,
    };
    let mut squares = 0.0;
    for axis in 0..3 {
        let u: Vec<f64> = points.iter().map(|p| explained(&sensor, p.force_g, axis)).collect();
        let scale = u.iter().fold(0.0f64, |m, v| m.max(v.abs())) > SCALE_DRIFT_FORCE_G
            && u.iter().any(|v| *v < -SCALE_DRIFT_FORCE_G);
        let values: Vec<f64> = points.iter().map(|p| p.accel_g[axis]).collect();
        let build = |order| points.iter().zip(&u).map(|(p, u)| accel_row(p.temp_c - ref_c, *u, order, scale)).collect();
        let (order, error) = choose_order(build, &values, folds);
        let solution = solve(&build(order), &values)?;
        coefficients_into(&mut fit.model.offset_g, axis, &solution[..=order], 1.0);
        if scale {
            coefficients_into(&mut fit.model.scale, axis, &solution[order + 1..], solution[order + 1]);
        }
        fit.scale_fitted |= scale;
        fit.accel_order[axis] = order;
        squares += error * error;
        fit_gyro_axis(&mut fit, points, ref_c, axis, folds)?;
    }
    fit.held_out_mg = mutant!("thermal-held-out-unscaled", (squares / 3.0).sqrt(), squares.sqrt()) * 1000.0;
    Ok(fit)
}

/// u_k: the part of axis `axis`'s reading the specific force explains at T_ref.
fn explained(sensor: &Mat3<f32>, force: Vec3<f64>, axis: usize) -> f64 {
    (0..3).map(|j| f64::from(sensor[axis][j]) * force[j]).sum()
}

fn fit_gyro_axis(
    fit: &mut ThermalFit,
    points: &[ThermalPoint],
    ref_c: f64,
    axis: usize,
    folds: Folds,
) -> Result<(), ThermalFitError> {
    let values: Vec<f64> = points.iter().map(|p| p.gyro_dps[axis]).collect();
    let build = |order| points.iter().map(|p| gyro_row(p.temp_c - ref_c, p.force_g, order)).collect();
    let (order, _) = choose_order(build, &values, folds);
    let solution = solve(&build(order), &values)?;
    coefficients_into(&mut fit.model.gyro_bias_dps, axis, &solution[..=order], 1.0);
    fit.gyro_order[axis] = order;
    Ok(())
}

#[cfg(test)]
mod tests;
