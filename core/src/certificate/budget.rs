//! The uncertainty budget of a session's calibration (GUM, JCGM 100, section 5: the law of propagation
//! of uncertainty). Every input that can err, each with its standard uncertainty, is moved by that
//! amount, the calibration computed again exactly as `calibrate` computes it, and how far each
//! parameter moved is that input's contribution; contributions of independent inputs add in squares.
//!
//! NOTE: moved through the whole computation rather than through the fit's covariance alone: the
//! adaptive session corrects its captures for a drift fitted with a prior, and only the computation
//! itself says how much of a temperature effect that leaves in the parameters.

use std::collections::BTreeMap;

use nalgebra::{Matrix3, Vector3};
use serde::{Deserialize, Serialize};

use super::estimate::Estimate;
use crate::fit::drift;
use crate::fit::{self, FitError, ModelChoice, Prediction, Quadratic};
use crate::session::Session;

/// Spread of the offset's drift per degree between parts, in g/degC: the prior of the session's
/// own drift fit ([`drift::SLOPE_PRIOR_G_PER_C`], from the Product Specification's zero-g change).
const OFFSET_TEMPCO_G_PER_C: f64 = drift::SLOPE_PRIOR_G_PER_C;
/// Spread of the sensitivity's change per degree, 1/degC: +-0.02 %/degC (MPU-6000/6050 Product
/// Specification rev 3.4, table 6.2, "Sensitivity Change vs. Temperature").
const SCALE_TEMPCO_PER_C: f64 = 2e-4;
/// The offset's slow wander over a session, in g: an accelerometer of this class shows a bias
/// instability of tens of ug in its Allan deviation (`accelcal noise` measures a board's own); 40 ug.
const BIAS_WANDER_G: f64 = 40e-6;
/// How far a board laid on a face by hand sits off it, in degrees (standard uncertainty): a degree,
/// twice the tilt ([`crate::limits::PLACEMENT_DEG`]) above which known orientations count as off.
const PLACEMENT_STD_DEG: f64 = 1.0;

/// The budget's components, each one row of the certificate's budget.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Component {
    /// The captures' noise (their measured scatter over the square root of their length), through
    /// the fit, scaled up where the residuals show more than the noise.
    Noise,
    /// Rounding of a capture's mean where the sensor's noise is below one count.
    Quantisation,
    /// The temperature's change during the session times the offset's and sensitivity's drift per
    /// degree (what the session's own drift fit leaves).
    Temperature,
    /// The offset's slow wander during the session.
    BiasWander,
    /// How far the board sat off the orientations a known-orientation model assumes.
    Placement,
}

/// One input that can err: how to move it, and by how much (its standard uncertainty).
struct Source {
    component: Component,
    /// Moves the session's captures by the input's standard uncertainty.
    moved: Box<dyn Fn(&Session) -> Session>,
    /// What the parameters would move by if the computation were perfect (the true change of a
    /// parameter the input itself is: a drift slope).
    ideal: Vec<f64>,
}

/// The budget: each parameter's contributions by component, and what the calibration's
/// uncertainty predicts at fresh orientations.
#[derive(Debug, Clone, PartialEq)]
pub struct Budget {
    /// Per parameter (in the estimate's order), the standard uncertainty of each component.
    pub contributions: Vec<BTreeMap<Component, f64>>,
    /// Per parameter, the combined standard uncertainty.
    pub standard: Vec<f64>,
    /// The | |a| - g | and tilt errors at a fresh orientation (RMS over the sphere, standard).
    pub prediction: Prediction,
}

/// The budget of `estimate`, the calibration of `session`.
pub fn budget(session: &Session, estimate: &Estimate) -> Result<Budget, FitError> {
    let choice = ModelChoice::Only(estimate.model);
    let n = estimate.values.len();
    let mut squares = vec![BTreeMap::<Component, f64>::new(); n];
    let mut covariance_terms: Vec<(Matrix3<f64>, Vector3<f64>)> = Vec::new();
    for source in sources(session, estimate) {
        let moved = Estimate::with(&(source.moved)(session), choice)?;
        for (k, square) in squares.iter_mut().enumerate() {
            let error = moved.values.get(k).copied().unwrap_or(estimate.values[k]) - estimate.values[k];
            *square.entry(source.component).or_default() += (error - source.ideal[k]).powi(2);
        }
        covariance_terms.push((moved.matrix - estimate.matrix, moved.offset - estimate.offset));
    }
    let contributions: Vec<BTreeMap<Component, f64>> =
        squares.iter().map(|s| s.iter().map(|(c, v)| (*c, v.sqrt())).collect()).collect();
    let standard = squares.iter().map(|s| s.values().sum::<f64>().sqrt()).collect();
    Ok(Budget { contributions, standard, prediction: predicted(estimate, &covariance_terms) })
}

/// The errors at fresh orientations that the parameters' moves imply: at true specific force u,
/// each input moves the corrected reading by E w, w = (u, 1), E = [dM M^-1 | -M do]; their
/// covariances add, sum_ab w_a w_b (E_a E_b^T).
fn predicted(estimate: &Estimate, moves: &[(Matrix3<f64>, Vector3<f64>)]) -> Prediction {
    let sensor = estimate.matrix.try_inverse().unwrap_or_else(Matrix3::identity);
    let mut terms: Quadratic = [[Matrix3::zeros(); 4]; 4];
    for (d_matrix, d_offset) in moves {
        let along = d_matrix * sensor;
        let column = |a: usize| if a < 3 { along.column(a).into_owned() } else { -(estimate.matrix * d_offset) };
        for (a, row) in terms.iter_mut().enumerate() {
            for (b, term) in row.iter_mut().enumerate() {
                *term += column(a) * column(b).transpose();
            }
        }
    }
    fit::predict(1.0, &terms)
}

/// Every input of the budget that can err for this session and model.
fn sources(session: &Session, estimate: &Estimate) -> Vec<Source> {
    let mut sources = capture_sources(session, estimate);
    let captures = session.dataset();
    // NOTE: captures without a temperature (a board's own stream) have no spread to move them by.
    if drift::carries_temperature(&captures) {
        sources.extend(temperature_sources(drift::mean_temp_c(&captures), estimate));
    }
    sources.extend((0..3).map(|axis| {
        let moved = move |s: &Session| shifted(s, |_, m| m[axis] += BIAS_WANDER_G);
        Source { component: Component::BiasWander, moved: Box::new(moved), ideal: vec![0.0; estimate.values.len()] }
    }));
    if estimate.uses_orientations() {
        sources.extend(placement_sources(session, estimate));
    }
    sources
}

/// Each capture's mean, per axis: its noise (inflated by the fit's factor) and, where the noise is
/// below one count, its rounding.
fn capture_sources(session: &Session, estimate: &Estimate) -> Vec<Source> {
    let mut sources = Vec::new();
    let zero = vec![0.0; estimate.values.len()];
    for (i, capture) in session.captures.iter().enumerate() {
        let stats = &capture.stats;
        let count = f64::from(stats.samples.max(1));
        let lsb_g = 1.0 / f64::from(stats.range.lsb_per_g());
        for axis in 0..3 {
            let std_g = f64::from(stats.std_g[axis]);
            let mut add = |component, u: f64| {
                let moved = move |s: &Session| shifted_one(s, i, axis, u);
                sources.push(Source { component, moved: Box::new(moved), ideal: zero.clone() });
            };
            add(Component::Noise, std_g / count.sqrt() * estimate.inflation);
            // NOTE: a scatter of a count or more dithers the rounding into the measured noise; below
            // it the mean can sit anywhere within the count (uniform: LSB / sqrt(12)).
            if std_g < lsb_g {
                add(Component::Quantisation, lsb_g / 12f64.sqrt());
            }
        }
    }
    sources
}

/// The offset's and the sensitivity's drift per degree, per axis, each at its spread between parts,
/// applied to the captures around their mean temperature `mean_c` (where the parameters are stated).
fn temperature_sources(mean_c: f64, estimate: &Estimate) -> Vec<Source> {
    let offset = estimate.offset;
    let mut sources = Vec::new();
    for axis in 0..3 {
        let mut ideal = vec![0.0; estimate.values.len()];
        if let Some(k) = estimate.slope_index(axis) {
            ideal[k] = OFFSET_TEMPCO_G_PER_C;
        }
        let moved = move |s: &Session| shifted(s, |t, m| m[axis] += OFFSET_TEMPCO_G_PER_C * (t - mean_c));
        sources.push(Source { component: Component::Temperature, moved: Box::new(moved), ideal });
        let moved = move |s: &Session| {
            shifted(s, |t, m| m[axis] += SCALE_TEMPCO_PER_C * (t - mean_c) * (m[axis] - offset[axis]))
        };
        sources.push(Source {
            component: Component::Temperature,
            moved: Box::new(moved),
            ideal: vec![0.0; estimate.values.len()],
        });
    }
    sources
}

/// Each capture tilted about the two horizontal lines by the placement's standard uncertainty: the
/// true specific force a = M (m - o) turned, read back through the calibration.
fn placement_sources(session: &Session, estimate: &Estimate) -> Vec<Source> {
    let angle = PLACEMENT_STD_DEG.to_radians();
    let (matrix, offset) = (estimate.matrix, estimate.offset);
    let sensor = matrix.try_inverse().unwrap_or_else(Matrix3::identity);
    let mut sources = Vec::new();
    for (i, capture) in session.captures.iter().enumerate() {
        let reading = Vector3::from(capture.stats.mean_g.map(f64::from));
        let up = (matrix * (reading - offset)).normalize();
        let first = up.cross(&Vector3::x()).try_normalize(1e-6).unwrap_or_else(|| up.cross(&Vector3::y()).normalize());
        for line in [first, up.cross(&first)] {
            let step = sensor * line.cross(&up) * angle;
            let moved = move |s: &Session| (0..3).fold(s.clone(), |s, axis| shifted_one(&s, i, axis, step[axis]));
            let ideal = vec![0.0; estimate.values.len()];
            sources.push(Source { component: Component::Placement, moved: Box::new(moved), ideal });
        }
    }
    sources
}

/// The session with one capture's mean moved by `amount` g along `axis`.
fn shifted_one(session: &Session, capture: usize, axis: usize, amount: f64) -> Session {
    let mut moved = session.clone();
    let mean = &mut moved.captures[capture].stats.mean_g[axis];
    *mean = (f64::from(*mean) + amount) as f32;
    moved
}

/// The session with every capture's mean changed by `change(temperature, mean)`.
fn shifted(session: &Session, change: impl Fn(f64, &mut [f64; 3])) -> Session {
    let mut moved = session.clone();
    for capture in &mut moved.captures {
        let mut mean = capture.stats.mean_g.map(f64::from);
        change(f64::from(capture.stats.temp_c), &mut mean);
        capture.stats.mean_g = mean.map(|v| v as f32);
    }
    moved
}
