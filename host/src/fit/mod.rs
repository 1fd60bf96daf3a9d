//! Fitting a calibration `a = M (m - o)` to a data file, by the models of DESIGN.md.

mod evaluate;
mod linear;

use std::fmt;
use std::str::FromStr;

use serde::Serialize;
use shared::linalg::{Mat3, Vec3};
use shared::{Model, Position};

use crate::data::Dataset;

pub use evaluate::{evaluate, Evaluation, RowEvaluation};

/// The model asked for on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ModelChoice {
    /// The richest model the data supports.
    Auto,
    /// One model.
    Only(Model),
}

impl FromStr for ModelChoice {
    type Err = String;

    fn from_str(name: &str) -> Result<Self, Self::Err> {
        if name == "auto" {
            return Ok(ModelChoice::Auto);
        }
        IMPLEMENTED
            .iter()
            .find(|m| m.name() == name)
            .map(|&m| ModelChoice::Only(m))
            .ok_or_else(|| format!("unknown model {name:?}; choose one of auto, {}", model_names()))
    }
}

/// The models this host can fit, richest first.
pub const IMPLEMENTED: [Model; 2] = [Model::Linear12, Model::SixPosition];

fn model_names() -> String {
    IMPLEMENTED.iter().map(|m| m.name()).collect::<Vec<_>>().join(", ")
}

/// Settings of a fit.
#[derive(Debug, Clone, Copy)]
pub struct FitOptions {
    /// |gravity| in output units (1 for g, 9.80665 for m/s^2).
    pub g: f64,
    /// Largest tilt in degrees for a reading to count as one of the six faces.
    pub face_tolerance_deg: f64,
}

impl Default for FitOptions {
    fn default() -> Self {
        FitOptions { g: 1.0, face_tolerance_deg: f64::from(shared::orientation::DEFAULT_FACE_TOLERANCE_DEG) }
    }
}

/// One fitted parameter with its standard error (none when the fit has no redundancy to estimate it).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Parameter {
    /// Name: `M11` ... `M33` for the matrix, `o_x` ... `o_z` for the offset.
    pub name: String,
    /// Value (M dimensionless, o in the file's unit).
    pub value: f64,
    /// Standard error from the Jacobian and the residual scatter.
    pub std_error: Option<f64>,
}

/// A fitted calibration: `a = matrix (m - offset)`, in the file's units.
#[derive(Debug, Clone, PartialEq)]
pub struct Fit {
    /// The model fitted.
    pub model: Model,
    /// Correction matrix M.
    pub matrix: Mat3<f64>,
    /// Offset o, in the file's unit.
    pub offset: Vec3<f64>,
    /// The model's dimensionless cost at the solution (residuals divided by g, squared, summed).
    pub cost: f64,
    /// Solver iterations (0 for closed-form and linear fits).
    pub iterations: usize,
    /// Every parameter with its standard error.
    pub parameters: Vec<Parameter>,
    /// Indices into the data set's rows of the rows the fit used.
    pub rows_used: Vec<usize>,
}

/// Why a fit could not run; each says what to add or change.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FitError {
    #[error("{model} needs at least {needed} rows with a known orientation (ref_x,ref_y,ref_z); the file has {found}")]
    TooFewReferences { model: &'static str, needed: usize, found: usize },
    #[error(
        "the known orientations do not determine {model}: they lie in one plane; \
         add a position with the {axis} axis pointing up or down"
    )]
    ReferencesInOnePlane { model: &'static str, axis: char },
    #[error(
        "six-position needs a reading with {} up (within {tolerance_deg} degrees); \
         add one, or choose a model that takes arbitrary positions",
        position.name()
    )]
    MissingPosition { position: Position, tolerance_deg: f64 },
    #[error("lines {first_line} and {second_line} are both {} up; keep one of them", position.name())]
    DuplicatePosition { position: Position, first_line: usize, second_line: usize },
    #[error("{model} is not available in this version; choose one of {available}")]
    NotAvailable { model: &'static str, available: String },
    #[error("the six positions do not determine the sensor: opposite faces read alike (is the file's unit right?)")]
    Degenerate,
}

/// Fits a model to a data set.
pub fn fit(dataset: &Dataset, choice: ModelChoice, options: &FitOptions) -> Result<Fit, FitError> {
    match choice {
        ModelChoice::Only(Model::SixPosition) => linear::six_position(dataset, options),
        ModelChoice::Only(Model::Linear12) => linear::linear12(dataset, options),
        ModelChoice::Only(other) => Err(FitError::NotAvailable { model: other.name(), available: model_names() }),
        ModelChoice::Auto => auto(dataset, options),
    }
}

/// The richest implemented model that fits; the error of the simplest when none does.
fn auto(dataset: &Dataset, options: &FitOptions) -> Result<Fit, FitError> {
    let mut last_error = None;
    for model in IMPLEMENTED {
        match fit(dataset, ModelChoice::Only(model), options) {
            Ok(fit) => return Ok(fit),
            Err(error) => last_error = Some(error),
        }
    }
    Err(last_error.unwrap_or(FitError::Degenerate))
}

impl fmt::Display for ModelChoice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ModelChoice::Auto => f.write_str("auto"),
            ModelChoice::Only(model) => f.write_str(model.name()),
        }
    }
}

/// Parameter list of a full 12-parameter calibration, with optional standard errors.
fn full_parameters(matrix: &Mat3<f64>, offset: &Vec3<f64>, errors: Option<(Mat3<f64>, Vec3<f64>)>) -> Vec<Parameter> {
    let mut parameters = Vec::with_capacity(12);
    for (i, row) in matrix.iter().enumerate() {
        for (j, &value) in row.iter().enumerate() {
            let std_error = errors.map(|(m, _)| m[i][j]);
            parameters.push(Parameter { name: format!("M{}{}", i + 1, j + 1), value, std_error });
        }
    }
    for (k, (&value, axis)) in offset.iter().zip(["x", "y", "z"]).enumerate() {
        let std_error = errors.map(|(_, o)| o[k]);
        parameters.push(Parameter { name: format!("o_{axis}"), value, std_error });
    }
    parameters
}
