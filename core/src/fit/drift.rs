//! A slow drift during a session (a board warming after power-on): the offset drift per degree
//! that, fitted with the nine parameters, best explains a session's captures, and the captures
//! corrected for it, so that the calibration is fitted to one temperature.

use nalgebra::{DMatrix, DVector, Matrix3, Vector3};
use shared::linalg::Vec3;

use super::{fit, Fit, FitError, FitOptions, Model, ModelChoice};
use crate::data::{Dataset, Row};
use crate::limits::{DRIFT_MIN_CAPTURES, DRIFT_MIN_CHANGE_C};

pub mod learned;

/// The spread of offset drifts expected before a session measures one, in g/degC: a prior that
/// keeps a slope from two or three spare captures from fitting their noise.
// NOTE: the Product Specification (rev 3.4, table 6.2) bounds the zero-g change over 0-70 degC to
// +-35 mg (x, y) and +-60 mg (z), 0.5-0.86 mg/degC; flight-controller users measure 0.7-2.2 mg/degC.
pub const SLOPE_PRIOR_G_PER_C: f64 = 1.0e-3;
/// Gauss-Newton steps at most (from the static fit it converges in a few).
const MAX_ROUNDS: usize = 20;
/// A step this small (its norm over M, o in g and c in g/degC) ends the steps.
const STEP_DONE: f64 = 1e-10;

/// The offset drift a session's captures show.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Drift {
    /// Offset change per degree, in g/degC.
    pub slope_g_per_c: Vec3<f64>,
    /// Lowest and highest die temperature of the captures, in degC.
    pub span_c: (f64, f64),
}

/// The offset drift per degree that, with the nine parameters, best explains the captures (in g,
/// with their temperatures): twelve parameters fitted together by Gauss-Newton from the static fit
/// (an upper-triangular M, which is ortho9's T K, o, and the slope c). `None` when the captures are
/// too few, the temperature did not move enough, or a fit fails.
pub fn fitted(captures: &Dataset) -> Option<Drift> {
    let span_c = span_c(captures);
    if captures.rows.len() < DRIFT_MIN_CAPTURES || span_c.1 - span_c.0 < DRIFT_MIN_CHANGE_C {
        return None;
    }
    let ref_c = mean_temp_c(captures);
    let start = ortho9(captures).ok()?;
    let matrix = Matrix3::from_fn(|i, j| start.matrix[i][j]);
    let mut p = Joint { matrix, offset: start.offset.into(), slope: Vector3::zeros() };
    for _ in 0..MAX_ROUNDS {
        let step = gauss_newton_step(captures, &p, ref_c)?;
        p.apply(&step);
        if step.norm() < STEP_DONE {
            break;
        }
    }
    Some(Drift { slope_g_per_c: p.slope.into(), span_c })
}

/// The twelve parameters of the joint fit.
struct Joint {
    matrix: Matrix3<f64>,
    offset: Vector3<f64>,
    slope: Vector3<f64>,
}

/// The upper triangle of M, in the order the step holds it.
const UPPER: [(usize, usize); 6] = [(0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2)];

impl Joint {
    fn apply(&mut self, step: &DVector<f64>) {
        UPPER.iter().enumerate().for_each(|(k, &(i, j))| self.matrix[(i, j)] += step[k]);
        self.offset += step.fixed_rows::<3>(6);
        self.slope += step.fixed_rows::<3>(9);
    }
}

/// One Gauss-Newton step of r_i = |M (m_i - o - c dT_i)| - 1 over the twelve parameters.
fn gauss_newton_step(captures: &Dataset, p: &Joint, ref_c: f64) -> Option<DVector<f64>> {
    let n = captures.rows.len();
    let (mut jacobian, mut residual) = (DMatrix::zeros(n + 3, 12), DVector::zeros(n + 3));
    // The prior: c_k ~ N(0, SLOPE_PRIOR^2), weighed against the captures' own noise.
    let weight = noise_g(captures) / SLOPE_PRIOR_G_PER_C;
    for k in 0..3 {
        jacobian[(n + k, 9 + k)] = weight;
        residual[n + k] = weight * p.slope[k];
    }
    for (i, row) in captures.rows.iter().enumerate() {
        let delta_c = temp_of(row) - ref_c;
        let v = Vector3::from(row.reading) - p.offset - p.slope * delta_c;
        let a = p.matrix * v;
        let along = a.normalize();
        let back = -(p.matrix.transpose() * along);
        UPPER.iter().enumerate().for_each(|(k, &(r, c))| jacobian[(i, k)] = along[r] * v[c]);
        jacobian.view_mut((i, 6), (1, 3)).copy_from(&back.transpose());
        jacobian.view_mut((i, 9), (1, 3)).copy_from(&(back * delta_c).transpose());
        residual[i] = a.norm() - 1.0;
    }
    let normal = jacobian.transpose() * &jacobian;
    normal.cholesky().map(|c| -c.solve(&(jacobian.transpose() * residual)))
}

/// The orientation-free fit of captures.
pub fn ortho9(captures: &Dataset) -> Result<Fit, FitError> {
    fit(captures, ModelChoice::Only(Model::Ortho9), &FitOptions::default())
}

/// The typical error of one capture's mean, in g: the median over the captures of the largest
/// axis' standard error (std / sqrt(n)).
fn noise_g(captures: &Dataset) -> f64 {
    let error = |row: &Row| {
        let std = row.std.unwrap_or_default().iter().copied().fold(0.0, f64::max);
        std / f64::from(row.count.unwrap_or(1).max(1)).sqrt()
    };
    let mut errors: Vec<f64> = captures.rows.iter().map(error).collect();
    errors.sort_by(f64::total_cmp);
    errors.get(errors.len() / 2).copied().unwrap_or(0.0)
}

/// A row's die temperature, in degC (NaN where the data set has none).
fn temp_of(row: &Row) -> f64 {
    row.temp_c.unwrap_or(f64::NAN)
}

/// The captures with every mean moved to what it would read at `ref_c`.
pub fn corrected(captures: &Dataset, drift: &Drift, ref_c: f64) -> Dataset {
    let shift = |row: &Row| {
        let delta = temp_of(row) - ref_c;
        Row { reading: [0, 1, 2].map(|k| row.reading[k] - drift.slope_g_per_c[k] * delta), ..row.clone() }
    };
    Dataset { rows: captures.rows.iter().map(shift).collect() }
}

/// The captures corrected for `drift`, if any, to their mean temperature.
pub fn at_mean_temperature(captures: &Dataset, drift: Option<&Drift>) -> Dataset {
    drift.map_or_else(|| captures.clone(), |d| corrected(captures, d, mean_temp_c(captures)))
}

/// The mean die temperature of the captures, in degC.
pub fn mean_temp_c(captures: &Dataset) -> f64 {
    let n = captures.rows.len().max(1) as f64;
    captures.rows.iter().map(temp_of).sum::<f64>() / n
}

/// The lowest and highest die temperature of the captures, degC, when they carry any: the span a
/// drift fitted to them was learned over.
pub fn temp_span_c(captures: &Dataset) -> Option<(f64, f64)> {
    let temps = captures.rows.iter().filter_map(|r| r.temp_c);
    temps.fold(None, |span, t| Some(span.map_or((t, t), |(low, high): (f64, f64)| (low.min(t), high.max(t)))))
}

/// Whether any capture carries a die temperature (a board's own stream carries none).
pub fn carries_temperature(captures: &Dataset) -> bool {
    captures.rows.iter().any(|r| r.temp_c.is_some())
}

/// The spread of the captures' die temperatures, in degC: (lowest, highest).
pub fn span_c(captures: &Dataset) -> (f64, f64) {
    let temps = captures.rows.iter().filter_map(|r| r.temp_c);
    temps.fold((f64::INFINITY, f64::NEG_INFINITY), |(low, high), t| (low.min(t), high.max(t)))
}

#[cfg(test)]
mod tests;
