//! The reports as the JSON objects of DESIGN.md ("Interfaces other programs rely on").

use serde::Serialize;

use super::{CalibrateReport, Comparison, FitReport, SessionReport};
use crate::calibration::CalibrationJson;
use crate::fit::{axis_angles_deg, parameters_by_name, Evaluation, Model, NoiseTest, Parameter, Prediction, Selection};

/// The object `accelcal fit --json` prints: the calibration (`model`, `matrix`, `offset`, `g`) and
/// the fit's statistics.
#[derive(Debug, Serialize)]
pub struct FitJson<'a> {
    /// The calibration, in the file's unit; `upload` takes it when `g` is 1.
    #[serde(flatten)]
    pub calibration: CalibrationJson,
    /// Dimensionless cost at the solution.
    pub cost: f64,
    /// Solver iterations (see `Fit::iterations`).
    pub iterations: usize,
    /// Every parameter by name: its value and standard errors (the reported one, from the residual
    /// scatter alone, from the captures' noise; null without redundancy or noise).
    #[serde(serialize_with = "parameters_by_name")]
    pub parameters: &'a [Parameter],
    /// Data-file lines the fit used.
    pub lines_used: &'a [usize],
    /// The residuals against the captures' own noise, when the file carries it.
    pub noise_test: Option<&'a NoiseTest>,
    /// Warnings (condition number, noise test).
    pub warnings: &'a [String],
    /// Errors of every row before and after, in output units and degrees.
    pub evaluation: &'a Evaluation,
    /// The other models on the same rows (with `--model auto`).
    pub comparison: Option<&'a Comparison>,
    /// Why `auto` chose the model, with every model's leave-one-out figure.
    pub selection: Option<&'a Selection>,
    /// The | |a| - g | (mg) and tilt (degrees) errors the uncertainty predicts at a fresh orientation.
    pub prediction: Option<&'a Prediction>,
    /// Angles between the sensor's axes x-y, x-z, y-z, in degrees (not for `diag6`, square by model).
    pub axis_angles_deg: Option<[f64; 3]>,
}

impl<'a> FitJson<'a> {
    /// The JSON view of a fit report.
    pub fn new(report: &'a FitReport) -> Self {
        let fit = &report.fit;
        FitJson {
            calibration: CalibrationJson::from_fit(fit, report.g),
            cost: fit.cost,
            iterations: fit.iterations,
            parameters: &fit.parameters,
            lines_used: &fit.lines_used,
            noise_test: fit.noise_test.as_ref(),
            warnings: &fit.warnings,
            evaluation: &report.evaluation,
            comparison: report.comparison.as_ref(),
            selection: fit.selection.as_ref(),
            prediction: fit.prediction.as_ref(),
            axis_angles_deg: axis_angles_deg(&fit.matrix).filter(|_| fit.model != Model::Diag6),
        }
    }
}

/// `accelcal fit --json`: the report as pretty JSON.
pub fn fit_report(report: &FitReport) -> String {
    to_pretty(&FitJson::new(report))
}

/// `accelcal calibrate --json`: the report as pretty JSON.
pub fn calibrate_report(report: &CalibrateReport) -> String {
    to_pretty(report)
}

/// `accelcal report --json`: the session report as pretty JSON.
pub fn session_report(report: &SessionReport) -> String {
    to_pretty(report)
}

/// A device calibration as pretty JSON (`download`, `info --json`).
pub fn calibration(calibration: &CalibrationJson) -> String {
    to_pretty(calibration)
}

fn to_pretty(value: &impl Serialize) -> String {
    // NOTE: the report types hold only numbers, strings, options and maps with string keys, which
    // always serialise.
    serde_json::to_string_pretty(value).unwrap_or_default()
}
