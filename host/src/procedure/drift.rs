//! A slow drift during a session (a board warming after power-on): the order that measures it (the
//! first position again at the end, A ... Z ... A), the offset drift per degree that the two captures
//! of A show, and the captures corrected for it, so that the fit sees one temperature.

use nalgebra::{DMatrix, DVector, Matrix3, Vector3};
use shared::linalg::Vec3;

use crate::fit::{self, Fit, FitError, FitOptions, Model, ModelChoice};
use crate::orientation::Orientation;
use crate::session::{CaptureRecord, Session};

/// The order in which the adaptive procedure asks for positions, chosen among orders from +Z for the
/// least error that a linear drift leaves in the twelve-parameter fit of all fourteen (and of the
/// first thirteen), at the session's end temperature, with the time a hand takes to turn counted:
/// most turns are 55-70 degrees (a face to a neighbouring corner, or a corner to the next), the
/// corners come first around the top and the bottom, the faces last.
// NOTE: the order before this one alternated faces and corners (125 degree turns); over the 20
// simulated sessions of tests/one_minute.rs it kept the board up to 63.2 s (this one 57.8 s) and
// ended 0.372 mg rms off at the end temperature (this one 0.297 mg). The search is
// host/tools/drift_order.py.
const ORDER: [&str; 14] = [
    "+Z", "+X-Y+Z", "+X+Y+Z", "+X+Y-Z", "-X+Y-Z", "-X-Y-Z", "-X-Y+Z", "+X-Y-Z", "-Z", "-X", "-Y", "+X", "+Y", "-X+Y+Z",
];
/// What the closing capture of the first position is called after it.
const AGAIN: &str = " again";
/// Smallest temperature span of the captures, in degC, that a drift per degree is fitted over;
/// below it the sensor did not warm and no correction is made.
// NOTE: the reading's resolution is 1/340 degC (register map 4.18); over a tenth of a degree a
// drift of 1 mg/degC moves the offset by 0.1 mg, half the default target.
const MIN_CHANGE_C: f64 = 0.1;
/// Fewest captures a drift is fitted from: twelve parameters and one more.
pub const MIN_CAPTURES: usize = 13;
/// The spread of offset drifts expected before a session measures one, in g/degC: a prior that
/// keeps a slope from two or three spare captures from fitting their noise.
// NOTE: the Product Specification (rev 3.4, table 6.2) bounds the zero-g change over 0-70 degC to
// +-35 mg (x, y) and +-60 mg (z), 0.5-0.86 mg/degC; flight-controller users measure 0.7-2.2 mg/degC.
pub const SLOPE_PRIOR_G_PER_C: f64 = 1.0e-3;
/// Gauss-Newton steps at most (from the static fit it converges in a few).
const MAX_ROUNDS: usize = 20;
/// A step this small (its norm over M, o in g and c in g/degC) ends the steps.
const STEP_DONE: f64 = 1e-10;

/// The wanted orientations in drift-cancelling order (those not in the table keep their place at
/// the end).
pub fn order(targets: &[Orientation]) -> Vec<Orientation> {
    let rank = |t: &Orientation| ORDER.iter().position(|n| *n == t.name).unwrap_or(ORDER.len());
    let mut ordered = targets.to_vec();
    ordered.sort_by_key(rank);
    ordered
}

/// The positions a session's captures were taken at: its captures but the closing one.
pub fn positions(session: &Session) -> usize {
    session.captures.iter().filter(|c| !c.name.ends_with(AGAIN)).count()
}

/// The closing capture: the first position again, under its own name.
pub fn closing(first: &Orientation) -> Orientation {
    Orientation { name: format!("{}{AGAIN}", first.name), ..first.clone() }
}

/// The offset drift a session's captures show.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Drift {
    /// Offset change per degree, in g/degC.
    pub slope_g_per_c: Vec3<f64>,
    /// Lowest and highest die temperature of the captures, in degC.
    pub span_c: (f64, f64),
}

/// The offset drift per degree that, with the nine parameters, best explains the captures: twelve
/// parameters fitted together by Gauss-Newton from the static fit (an upper-triangular M, which is
/// ortho9's T K, o, and the slope c). `None` when the captures are too few, the temperature did
/// not move enough, or a fit fails.
pub fn fitted(session: &Session) -> Option<Drift> {
    let span_c = span_c(session);
    if session.captures.len() < MIN_CAPTURES || span_c.1 - span_c.0 < MIN_CHANGE_C {
        return None;
    }
    let ref_c = mean_temp_c(session);
    let start = ortho9(session).ok()?;
    let mut p = Joint {
        matrix: Matrix3::from_fn(|i, j| start.matrix[i][j]),
        offset: start.offset.into(),
        slope: Vector3::zeros(),
    };
    for _ in 0..MAX_ROUNDS {
        let step = gauss_newton_step(session, &p, ref_c)?;
        p.apply(&step);
        if step.norm() < STEP_DONE {
            break;
        }
    }
    Some(Drift { slope_g_per_c: p.slope.into(), span_c })
}

/// Whether the temperature moved enough for a drift, yet the captures would still be too few to fit
/// it after `more` further captures.
pub fn unfitted_after(session: &Session, more: usize) -> bool {
    let span_c = span_c(session);
    span_c.1 - span_c.0 >= MIN_CHANGE_C && session.captures.len() + more < MIN_CAPTURES
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
fn gauss_newton_step(session: &Session, p: &Joint, ref_c: f64) -> Option<DVector<f64>> {
    let n = session.captures.len();
    let (mut jacobian, mut residual) = (DMatrix::zeros(n + 3, 12), DVector::zeros(n + 3));
    // The prior: c_k ~ N(0, SLOPE_PRIOR^2), weighed against the captures' own noise.
    let weight = noise_g(session) / SLOPE_PRIOR_G_PER_C;
    for k in 0..3 {
        jacobian[(n + k, 9 + k)] = weight;
        residual[n + k] = weight * p.slope[k];
    }
    for (row, capture) in session.captures.iter().enumerate() {
        let delta_c = f64::from(capture.stats.temp_c) - ref_c;
        let v = Vector3::from(capture.stats.mean_g.map(f64::from)) - p.offset - p.slope * delta_c;
        let a = p.matrix * v;
        let along = a.normalize();
        let back = -(p.matrix.transpose() * along);
        UPPER.iter().enumerate().for_each(|(k, &(i, j))| jacobian[(row, k)] = along[i] * v[j]);
        jacobian.view_mut((row, 6), (1, 3)).copy_from(&back.transpose());
        jacobian.view_mut((row, 9), (1, 3)).copy_from(&(back * delta_c).transpose());
        residual[row] = a.norm() - 1.0;
    }
    let normal = jacobian.transpose() * &jacobian;
    normal.cholesky().map(|c| -c.solve(&(jacobian.transpose() * residual)))
}

/// The orientation-free fit of a session's captures.
pub fn ortho9(session: &Session) -> Result<Fit, FitError> {
    fit::fit(&session.dataset(), ModelChoice::Only(Model::Ortho9), &FitOptions::default())
}

/// The typical error of one capture's mean, in g: the median over the captures of the largest
/// axis' standard error (std / sqrt(n)).
fn noise_g(session: &Session) -> f64 {
    let mut errors: Vec<f64> = session
        .captures
        .iter()
        .map(|c| {
            f64::from(c.stats.std_g.iter().copied().fold(0.0, f32::max)) / f64::from(c.stats.samples.max(1)).sqrt()
        })
        .collect();
    errors.sort_by(f64::total_cmp);
    errors.get(errors.len() / 2).copied().unwrap_or(0.0)
}

/// The session with every capture's mean moved to what it would read at `ref_c`.
pub fn corrected(session: &Session, drift: &Drift, ref_c: f64) -> Session {
    let shift = |capture: &CaptureRecord| {
        let mut moved = capture.clone();
        let delta = f64::from(capture.stats.temp_c) - ref_c;
        for k in 0..3 {
            moved.stats.mean_g[k] -= (drift.slope_g_per_c[k] * delta) as f32;
        }
        moved
    };
    Session { captures: session.captures.iter().map(shift).collect(), ..session.clone() }
}

/// The session's captures corrected for `drift`, if any, to their mean temperature.
pub fn at_mean_temperature(session: &Session, drift: Option<&Drift>) -> Session {
    drift.map_or_else(|| session.clone(), |d| corrected(session, d, mean_temp_c(session)))
}

/// The mean die temperature of the session's captures, in degC.
pub fn mean_temp_c(session: &Session) -> f64 {
    let n = session.captures.len().max(1) as f64;
    session.captures.iter().map(|c| f64::from(c.stats.temp_c)).sum::<f64>() / n
}

/// The spread of the captures' die temperatures, in degC: (lowest, highest).
pub fn span_c(session: &Session) -> (f64, f64) {
    let temps = session.captures.iter().map(|c| f64::from(c.stats.temp_c));
    temps.fold((f64::INFINITY, f64::NEG_INFINITY), |(low, high), t| (low.min(t), high.max(t)))
}

#[cfg(test)]
mod tests {
    use shared::linalg;
    use shared::protocol::CaptureStats;
    use shared::AccelRange;

    use super::*;
    use crate::orientation::{corners, faces};

    /// A noise-free capture of a sensor with M^-1 = diag(1.01, 0.99, 1.02) plus a cross term, offset
    /// o(T) = o + c (T - 22), at `up` and die temperature `temp_c`.
    fn capture(target: &Orientation, temp_c: f64, slope: Vec3<f64>, std_g: f32) -> CaptureRecord {
        let sensor = [[1.01, 0.002, -0.004], [0.0, 0.99, 0.003], [0.0, 0.0, 1.02]];
        let offset = [0.03, -0.01, -0.08];
        let reading =
            linalg::add(linalg::mul_vec(&sensor, target.up), linalg::add(offset, linalg::scale(slope, temp_c - 22.0)));
        let stats = CaptureStats {
            samples: 200,
            seconds: 2.0,
            mean_g: reading.map(|v| v as f32),
            std_g: [std_g; 3],
            gyro_mean_dps: [0.0; 3],
            gyro_std_dps: [0.05; 3],
            temp_c: temp_c as f32,
            clipped: 0,
            range: AccelRange::G2,
        };
        CaptureRecord::now(&target.name, Some(target.clone()), None, stats)
    }

    /// Noise-free captures that state a scatter of `std_g` per sample (200 samples each).
    fn warming_session(slope: Vec3<f64>, std_g: f32) -> Session {
        let mut targets = order(&[faces(), corners()].concat());
        targets.push(closing(&targets[0]));
        let captures = targets.iter().enumerate().map(|(i, t)| capture(t, 21.5 + 0.07 * i as f64, slope, std_g));
        Session { captures: captures.collect(), ..Session::default() }
    }

    #[test]
    fn the_fitted_drift_is_the_sensor_s_own_and_the_corrected_fit_its_static_calibration() {
        // Captures that say they are known to 0.07 ug: the prior weighs nothing beside them.
        let slope = [0.75e-3, -0.7e-3, 1.4e-3];
        let session = warming_session(slope, 1e-6);
        let drift = fitted(&session).expect("a drift over 1 degC");
        for k in 0..3 {
            assert!((drift.slope_g_per_c[k] - slope[k]).abs() < 2e-6, "{:?} vs {slope:?}", drift.slope_g_per_c);
        }
        // At 22 degC the corrected captures read the static sensor: the fit's offset is o.
        let fit = ortho9(&corrected(&session, &drift, 22.0)).unwrap();
        for (k, o) in [0.03, -0.01, -0.08].iter().enumerate() {
            assert!((fit.offset[k] - o).abs() < 2e-6, "{:?}", fit.offset);
        }
    }

    #[test]
    fn the_prior_draws_a_slope_from_captures_of_ordinary_noise_towards_zero() {
        // Means known to 0.2 mg, as the default session's: the prior of 1 mg/degC weighs as much as
        // a spare capture or two, so the same slopes come out smaller (measured 0.83, 0.48, 0.91 of
        // the truth), never larger or reversed.
        let slope = [0.75e-3, -0.7e-3, 1.4e-3];
        let drift = fitted(&warming_session(slope, 2.8e-3)).unwrap();
        for k in 0..3 {
            let ratio = drift.slope_g_per_c[k] / slope[k];
            assert!((0.4..0.95).contains(&ratio), "{:?} vs {slope:?}", drift.slope_g_per_c);
        }
    }

    #[test]
    fn no_drift_is_fitted_when_the_temperature_stayed_or_the_captures_are_too_few() {
        let mut still = warming_session([1e-3; 3], 2.8e-3);
        still.captures.iter_mut().for_each(|c| c.stats.temp_c = 25.0);
        assert_eq!(fitted(&still), None);
        let mut few = warming_session([1e-3; 3], 2.8e-3);
        few.captures.truncate(MIN_CAPTURES - 1);
        assert_eq!(fitted(&few), None);
        // One capture short: the closing one makes it fitted; a board that stayed needs none.
        assert!(unfitted_after(&few, 0) && !unfitted_after(&few, 1));
        assert!(!unfitted_after(&still, 0));
    }

    #[test]
    fn the_order_is_the_table_s_and_closes_on_its_first_position() {
        let ordered = order(&[faces(), corners()].concat());
        let names: Vec<&str> = ordered.iter().map(|t| t.name.as_str()).collect();
        assert_eq!(names, ORDER);
        assert_eq!(closing(&ordered[0]).name, "+Z again");
        assert_eq!(closing(&ordered[0]).up, ordered[0].up);
    }
}
