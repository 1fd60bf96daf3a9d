//! The reports as the JSON objects of DESIGN.md ("Interfaces other programs rely on").

use std::collections::BTreeMap;

use serde::Serialize;

use super::{CalibrateReport, Comparison, FitReport};
use crate::calibration::CalibrationJson;
use crate::fit::{Evaluation, NoiseTest};

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
    /// Standard error of every parameter (null without redundancy).
    pub std_errors: BTreeMap<&'a str, Option<f64>>,
    /// Every parameter's value, by name.
    pub parameters: BTreeMap<&'a str, f64>,
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
}

impl<'a> FitJson<'a> {
    /// The JSON view of a fit report.
    pub fn new(report: &'a FitReport) -> Self {
        let fit = &report.fit;
        FitJson {
            calibration: CalibrationJson::from_fit(fit, report.g),
            cost: fit.cost,
            iterations: fit.iterations,
            std_errors: fit.parameters.iter().map(|p| (p.name.as_str(), p.std_error)).collect(),
            parameters: fit.parameters.iter().map(|p| (p.name.as_str(), p.value)).collect(),
            lines_used: &fit.lines_used,
            noise_test: fit.noise_test.as_ref(),
            warnings: &fit.warnings,
            evaluation: &report.evaluation,
            comparison: report.comparison.as_ref(),
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

/// A device calibration as pretty JSON (`download`, `info --json`).
pub fn calibration(calibration: &CalibrationJson) -> String {
    to_pretty(calibration)
}

fn to_pretty(value: &impl Serialize) -> String {
    // NOTE: the report types hold only numbers, strings, options and maps with string keys, which
    // always serialise.
    serde_json::to_string_pretty(value).unwrap_or_default()
}
