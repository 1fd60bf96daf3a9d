//! A slow drift during a session (a board warming after power-on): the order that measures it (the
//! first position again at the end, A ... Z ... A), the offset drift per degree that the two captures
//! of A show, and the captures corrected for it, so that the fit sees one temperature.

use nalgebra::{Matrix3, Vector3};
use shared::linalg::{self, Vec3};

use crate::fit::{self, Fit, FitError, FitOptions, Model, ModelChoice};
use crate::orientation::Orientation;
use crate::session::{CaptureRecord, Session};

/// The order in which the adaptive procedure asks for positions: every prefix from ten on spreads
/// over the sphere (faces and corners alternate, opposite ones apart), so that it may stop early.
const ORDER: [&str; 14] = [
    "+Z", "+X+Y-Z", "-X", "+X-Y+Z", "+Y", "-X-Y-Z", "-Z", "-X+Y+Z", "+X", "-Y", "-X+Y-Z", "+X+Y+Z", "-X-Y+Z", "+X-Y-Z",
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
/// Rounds of the alternating fit at most.
const MAX_ROUNDS: usize = 20;
/// A slope step this small (g/degC, 1 ug/degC) ends the rounds.
const STEP_DONE_G_PER_C: f64 = 1e-6;

/// The wanted orientations in drift-cancelling order (those not in the table keep their place at
/// the end).
pub fn order(targets: &[Orientation]) -> Vec<Orientation> {
    let rank = |t: &Orientation| ORDER.iter().position(|n| *n == t.name).unwrap_or(ORDER.len());
    let mut ordered = targets.to_vec();
    ordered.sort_by_key(rank);
    ordered
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

/// The offset drift per degree that, with the nine parameters, best explains the captures (twelve
/// parameters in all): the nine fitted to captures corrected by the slope, the slope moved by the
/// least-squares step its residuals ask for, in turn, until the step is negligible. `None` when the
/// captures are too few, the temperature did not move enough, or a fit fails.
pub fn fitted(session: &Session) -> Option<Drift> {
    let span_c = span_c(session);
    if session.captures.len() < MIN_CAPTURES || span_c.1 - span_c.0 < MIN_CHANGE_C {
        return None;
    }
    let ref_c = mean_temp_c(session);
    let mut drift = Drift { slope_g_per_c: [0.0; 3], span_c };
    for _ in 0..MAX_ROUNDS {
        let fit = ortho9(&corrected(session, &drift, ref_c)).ok()?;
        let step = slope_step(session, &drift, &fit, ref_c)?;
        drift.slope_g_per_c = linalg::add(drift.slope_g_per_c, step);
        if linalg::norm(step) < STEP_DONE_G_PER_C {
            break;
        }
    }
    Some(drift)
}

/// The orientation-free fit of a session's captures.
pub fn ortho9(session: &Session) -> Result<Fit, FitError> {
    fit::fit(&session.dataset(), ModelChoice::Only(Model::Ortho9), &FitOptions::default())
}

/// The Gauss-Newton step of the slope with the nine parameters held: r_i = |M (m_i - o - c dT_i)| - 1
/// changes by -(a_i / |a_i|)^T M dT_i per unit of c.
fn slope_step(session: &Session, drift: &Drift, fit: &Fit, ref_c: f64) -> Option<Vec3<f64>> {
    let (mut normal, mut right) = (Matrix3::<f64>::zeros(), Vector3::<f64>::zeros());
    let matrix = Matrix3::from_fn(|i, j| fit.matrix[i][j]);
    for capture in &corrected(session, drift, ref_c).captures {
        let reading = Vector3::from(capture.stats.mean_g.map(f64::from));
        let corrected = matrix * (reading - Vector3::from(fit.offset));
        let gradient = -(matrix.transpose() * corrected.normalize()) * (f64::from(capture.stats.temp_c) - ref_c);
        normal += gradient * gradient.transpose();
        right -= gradient * (corrected.norm() - 1.0);
    }
    normal.try_inverse().map(|inverse| (inverse * right).into())
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
