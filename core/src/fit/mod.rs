//! Fitting a calibration `a = M (m - o)` to a data file, by the models of DESIGN.md.

mod covariance;
pub mod drift;
mod evaluate;
mod faces;
pub mod gyro;
pub mod hysteresis;
mod influence;
mod left_out;
mod linear;
mod linearised;
mod model;
mod models;
mod nonlinear;
mod normalization;
mod observability;
mod ortho9;
mod prediction;
mod selection;
mod shape;
mod statistics;
pub mod thermal;
mod uncertainty;
mod verdict;

use std::borrow::Cow;
use std::collections::HashSet;
use std::fmt;
use std::str::FromStr;

use serde::Serialize;
use shared::linalg::{Mat3, Vec3};
use shared::Position;

use crate::data::Dataset;

pub use evaluate::{evaluate, Evaluation, RowEvaluation};
pub use left_out::leave_one_out_rms;
pub use model::Model;
pub use prediction::{axis_angles_deg, predict, Prediction, Quadratic};
pub use selection::Selection;
pub use statistics::{misalignment_deg, NoiseTest};

/// The model asked for on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ModelChoice {
    /// The model that best predicts rows left out of its fit (leave-one-out).
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
        RICHEST_FIRST
            .iter()
            .find(|m| m.name() == name)
            .map(|&m| ModelChoice::Only(m))
            .ok_or_else(|| format!("unknown model {name:?}; choose one of auto, {}", model_names()))
    }
}

impl fmt::Display for ModelChoice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ModelChoice::Auto => f.write_str("auto"),
            ModelChoice::Only(model) => f.write_str(model.name()),
        }
    }
}

/// Every model, richest first: the order in which models are listed, and in which `auto` falls back
/// to the first that fits when none can be tested on left-out rows.
///
/// NOTE: `reference-norm12` uses every row (known orientations and |a| = g), `linear12` only the
/// rows of known orientation; `ortho9` needs no orientation; the six-position closed form uses only
/// six readings, so it comes after the fits over all positions.
pub const RICHEST_FIRST: [Model; 5] =
    [Model::ReferenceNorm12, Model::Linear12, Model::Ortho9, Model::Diag6, Model::SixPosition];

fn model_names() -> String {
    RICHEST_FIRST.iter().map(|m| m.name()).collect::<Vec<_>>().join(", ")
}

/// Settings of a fit.
#[derive(Debug, Clone, PartialEq)]
pub struct FitOptions {
    /// |gravity| in output units (1 for g, 9.80665 for m/s^2).
    pub g: f64,
    /// Largest tilt in degrees for a reading to count as one of the six faces.
    pub face_tolerance_deg: f64,
    /// Data rows (1-based, in file order) to fit; `None`: all. The others are held out for testing.
    pub training_rows: Option<Vec<usize>>,
    /// Data rows (1-based) whose known orientation the fit uses; `None`: every row that has one.
    /// The other rows count as |a| = g only.
    pub reference_rows: Option<Vec<usize>>,
}

impl Default for FitOptions {
    fn default() -> Self {
        FitOptions {
            g: 1.0,
            face_tolerance_deg: crate::limits::FACE_TOLERANCE_DEG,
            training_rows: None,
            reference_rows: None,
        }
    }
}

impl FitOptions {
    /// The rows the fit sees: the training rows, with references only where they are to be used.
    fn training_set<'a>(&self, dataset: &'a Dataset) -> Result<Cow<'a, Dataset>, FitError> {
        let count = dataset.rows.len();
        for &row in self.training_rows.iter().chain(&self.reference_rows).flatten() {
            if row == 0 || row > count {
                return Err(FitError::NoSuchRow { row, rows: count });
            }
        }
        if self.training_rows.is_none() && self.reference_rows.is_none() {
            return Ok(Cow::Borrowed(dataset));
        }
        let set = |rows: &Option<Vec<usize>>| rows.as_ref().map(|r| r.iter().copied().collect::<HashSet<usize>>());
        let (training, references) = (set(&self.training_rows), set(&self.reference_rows));
        let rows = dataset
            .rows
            .iter()
            .enumerate()
            .filter(|(i, _)| training.as_ref().is_none_or(|rows| rows.contains(&(i + 1))))
            .map(|(i, row)| {
                let mut row = row.clone();
                if references.as_ref().is_some_and(|rows| !rows.contains(&(i + 1))) {
                    row.reference = None;
                }
                row
            })
            .collect();
        Ok(Cow::Owned(Dataset { rows }))
    }
}

/// One fitted parameter with its standard error (none when the fit has no redundancy to estimate it).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Parameter {
    /// Name: `M11` ... `M33` for a full matrix, `a_yz` ... `s_z` for T K, `o_x` ... `o_z` the offset.
    pub name: &'static str,
    /// Value (M dimensionless, o in the file's unit).
    pub value: f64,
    /// The standard error reported: the noise-based one, scaled up when the residuals are
    /// significantly larger than the noise explains, so that it holds whether the scatter comes from
    /// the noise or from what the model misses; the scatter-based one where the file gives no noise.
    pub std_error: Option<f64>,
    /// Standard error from the Jacobian and the residual scatter (none without redundancy).
    pub scatter_std_error: Option<f64>,
    /// Standard error from the noise the captures measured (`count`, `std_*`), where the data has it.
    pub noise_std_error: Option<f64>,
}

impl Parameter {
    /// A parameter with its scatter- and noise-based standard errors; `inflation` scales the noise's
    /// for what the residuals show beyond the noise.
    fn new(name: &'static str, value: f64, errors: [Option<f64>; 2], inflation: f64) -> Self {
        let [scatter_std_error, noise_std_error] = errors;
        let std_error = noise_std_error.map(|e| e * inflation).or(scatter_std_error);
        Parameter { name, value, std_error, scatter_std_error, noise_std_error }
    }
}

/// Standard errors of a full calibration's M and o.
type FullErrors = Option<(Mat3<f64>, Vec3<f64>)>;

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
    /// Solver iterations: residual evaluations of the levenberg-marquardt crate, iterations of the
    /// fixed-size `ortho9` solver (one 9x9 solve each), 0 for closed-form fits.
    pub iterations: usize,
    /// Every parameter with its standard error.
    pub parameters: Vec<Parameter>,
    /// Data-file lines the fit used.
    pub lines_used: Vec<usize>,
    /// The residuals tested against the noise the captures measured, where the data carries it.
    pub noise_test: Option<NoiseTest>,
    /// Things the user should know: a poor condition number, a model that does not fit the noise.
    pub warnings: Vec<String>,
    /// With `auto`: why this model, and every model's leave-one-out figure.
    pub selection: Option<Selection>,
    /// The errors the parameters' uncertainty predicts at a fresh orientation.
    pub prediction: Option<Prediction>,
}

/// Why a fit could not run; each says what to add or change.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FitError {
    #[error("{model} needs at least {needed} rows with a known orientation (ref_x,ref_y,ref_z); the file has {found}")]
    TooFewReferences { model: &'static str, needed: usize, found: usize },
    #[error("{model} needs at least {needed} positions; the data has {found}: add {} more", needed - found)]
    TooFewPositions { model: &'static str, needed: usize, found: usize },
    #[error(
        "the known orientations do not determine {model}: they lie in one plane; \
         add a position with the {axis} axis pointing up or down"
    )]
    ReferencesInOnePlane { model: &'static str, axis: char },
    #[error(
        "{model} cannot be determined: no position has the {axis} axis pointing {} (within {} degrees); \
         add one with {}{axis} up",
        if *up { "up" } else { "down" }, crate::limits::axis_spread_deg(), if *up { "+" } else { "-" }
    )]
    NoSpread { model: &'static str, axis: char, up: bool },
    #[error("{model} cannot be determined from these positions: {parameter} is not observable; add positions spread over the sphere")]
    Unobservable { model: &'static str, parameter: String },
    #[error(
        "six-position needs a reading with {} up (within {tolerance_deg} degrees); \
         add one, or choose a model that takes arbitrary positions",
        position.name()
    )]
    MissingPosition { position: Position, tolerance_deg: f64 },
    #[error("lines {first_line} and {second_line} are both {} up; keep one of them", position.name())]
    DuplicatePosition { position: Position, first_line: usize, second_line: usize },
    #[error("row {row} does not exist: the file has {rows} data rows")]
    NoSuchRow { row: usize, rows: usize },
    #[error("the solver did not converge ({reason}); check the file's unit and --g")]
    NotConverged { reason: String },
    #[error("the positions do not determine the sensor: opposite faces read alike (is the file's unit right?)")]
    Degenerate,
    #[error("no model can be fitted to these rows; the closest is {closest}{short}: {reason}")]
    NothingFits { closest: &'static str, short: String, reason: String },
}

/// Fits a model (or, for `auto`, the one that best predicts rows it did not see) to the training rows
/// of a data set.
pub fn fit(dataset: &Dataset, choice: ModelChoice, options: &FitOptions) -> Result<Fit, FitError> {
    let training = options.training_set(dataset)?;
    match choice {
        ModelChoice::Only(model) => fit_model(&training, model, options),
        ModelChoice::Auto => selection::choose(&training, options),
    }
}

/// Every model on the same rows, richest first, for comparison.
pub fn fit_all(dataset: &Dataset, options: &FitOptions) -> Vec<(Model, Result<Fit, FitError>)> {
    match options.training_set(dataset) {
        Ok(training) => RICHEST_FIRST.iter().map(|&m| (m, fit_model(&training, m, options))).collect(),
        Err(error) => RICHEST_FIRST.iter().map(|&m| (m, Err(error.clone()))).collect(),
    }
}

fn fit_model(training: &Dataset, model: Model, options: &FitOptions) -> Result<Fit, FitError> {
    match model {
        Model::SixPosition => linear::six_position(training, options),
        Model::Linear12 => linear::linear12(training, options),
        Model::ReferenceNorm12 | Model::Ortho9 | Model::Diag6 => models::least_squares(training, model, options),
    }
}

/// Parameter list of a full 12-parameter calibration, with scatter- and noise-based standard errors
/// (the latter scaled by `inflation` where reported).
fn full_parameters(
    matrix: &Mat3<f64>,
    offset: &Vec3<f64>,
    [scatter, noise]: [FullErrors; 2],
    inflation: f64,
) -> Vec<Parameter> {
    let name = |k: usize| models::parameter_name(shape::Shape::Full, k);
    let mut parameters = Vec::with_capacity(12);
    for (i, row) in matrix.iter().enumerate() {
        for (j, &value) in row.iter().enumerate() {
            let (a, b) = (scatter.map(|(m, _)| m[i][j]), noise.map(|(m, _)| m[i][j]));
            parameters.push(Parameter::new(name(3 * i + j), value, [a, b], inflation));
        }
    }
    for (k, &value) in offset.iter().enumerate() {
        let (a, b) = (scatter.map(|(_, o)| o[k]), noise.map(|(_, o)| o[k]));
        parameters.push(Parameter::new(name(9 + k), value, [a, b], inflation));
    }
    parameters
}
