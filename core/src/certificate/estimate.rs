//! What a session's calibration comes out as, computed the way `calibrate` computes it, so that the
//! uncertainty budget can ask how it moves when one of its inputs moves.

use nalgebra::{Matrix3, Vector3};

use crate::fit::{self, FitError, FitOptions, Model, ModelChoice};
use crate::session::Session;

/// Names of the offset drift slopes, in g/degC, when the session fitted them.
pub const SLOPE_NAMES: [&str; 3] = ["c_x", "c_y", "c_z"];

/// A session's calibration: every parameter by name, and the M and o they make.
#[derive(Debug, Clone, PartialEq)]
pub struct Estimate {
    /// The model fitted.
    pub model: Model,
    /// Parameter names: the model's, then the drift slopes when fitted.
    pub names: Vec<String>,
    /// Their values (M dimensionless, o in g, slopes in g/degC).
    pub values: Vec<f64>,
    /// M of a = M (m - o), at the captures' mean temperature.
    pub matrix: Matrix3<f64>,
    /// o, in g, at the captures' mean temperature.
    pub offset: Vector3<f64>,
    /// How much the fit scaled the noise's errors up for what its residuals show beyond the noise.
    pub inflation: f64,
}

impl Estimate {
    /// The calibration of `session` as `calibrate` fits it: an adaptive session's corrected for its
    /// fitted drift (whose slopes become parameters), any other's by its session's model.
    pub fn of(session: &Session) -> Result<Self, FitError> {
        Estimate::with(session, session.model())
    }

    /// The same with the model fixed (so that a small change of the captures cannot switch models).
    pub fn with(session: &Session, choice: ModelChoice) -> Result<Self, FitError> {
        let fitted = session.fitted();
        let (fit, drift) = (fit::fit(&fitted.captures, choice, &FitOptions::default())?, fitted.drift);
        let mut names: Vec<String> = fit.parameters.iter().map(|p| p.name.to_owned()).collect();
        let mut values: Vec<f64> = fit.parameters.iter().map(|p| p.value).collect();
        if let Some(drift) = drift {
            names.extend(SLOPE_NAMES.map(String::from));
            values.extend(drift.slope_g_per_c);
        }
        Ok(Estimate {
            model: fit.model,
            names,
            values,
            matrix: Matrix3::from_fn(|i, j| fit.matrix[i][j]),
            offset: Vector3::from(fit.offset),
            inflation: inflation(&fit),
        })
    }

    /// The index of a drift slope's parameter, when the session fitted the drift.
    pub fn slope_index(&self, axis: usize) -> Option<usize> {
        self.names.iter().position(|n| n == SLOPE_NAMES[axis])
    }

    /// Whether the model takes the captures' orientations as known (so that placement errs it).
    pub fn uses_orientations(&self) -> bool {
        matches!(self.model, Model::SixPosition | Model::Linear12 | Model::ReferenceNorm12)
    }
}

/// The ratio of the reported standard errors to the noise-based ones (1 when the residuals fit the
/// noise, or when the fit has no noise-based errors).
fn inflation(fit: &fit::Fit) -> f64 {
    let ratio = |p: &fit::Parameter| Some(p.std_error? / p.noise_std_error.filter(|e| *e > 0.0)?);
    fit.parameters.iter().find_map(ratio).filter(|r| r.is_finite()).unwrap_or(1.0).max(1.0)
}
