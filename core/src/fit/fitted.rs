//! What a fit is asked (`FitOptions`) and what it gives: the fit with its parameters and their
//! standard errors and, with `auto`, why that model (`Fit`, `Parameter`, `Selection`). Below the
//! choice among the models and the report; [`super::error`] says why a fit could not run.

use std::borrow::Cow;
use std::collections::HashSet;

use serde::Serialize;
use shared::linalg::{Mat3, Vec3};

use super::shape::{parameter_name, Shape};
use super::{FitError, Model, NoiseTest, Prediction};
use crate::data::Dataset;

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
    pub(super) fn training_set<'a>(&self, dataset: &'a Dataset) -> Result<Cow<'a, Dataset>, FitError> {
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
    pub(super) fn new(name: &'static str, value: f64, errors: [Option<f64>; 2], inflation: f64) -> Self {
        let [scatter_std_error, noise_std_error] = errors;
        let std_error = noise_std_error.map(|e| e * inflation).or(scatter_std_error);
        Parameter { name, value, std_error, scatter_std_error, noise_std_error }
    }
}

/// Standard errors of a full calibration's M and o.
type FullErrors = Option<(Mat3<f64>, Vec3<f64>)>;

/// Why `auto` chose its model, with every model's leave-one-out figure.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Selection {
    /// One sentence: the model chosen and the evidence.
    pub reason: String,
    /// Every model, richest first, with the RMS of | |a| - g | at each row left out of its fit, in
    /// output units; `None` where the model cannot be fitted with a row left out.
    pub leave_one_out: Vec<(&'static str, Option<f64>)>,
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

/// Parameter list of a full 12-parameter calibration, with scatter- and noise-based standard errors
/// (the latter scaled by `inflation` where reported).
pub(super) fn full_parameters(
    matrix: &Mat3<f64>,
    offset: &Vec3<f64>,
    [scatter, noise]: [FullErrors; 2],
    inflation: f64,
) -> Vec<Parameter> {
    let name = |k: usize| parameter_name(Shape::Full, k);
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
