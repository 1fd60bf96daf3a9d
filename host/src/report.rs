//! What `accelcal fit` prints: a table for a person, or the JSON object of DESIGN.md.

use std::collections::BTreeMap;
use std::fmt::Write;

use serde::Serialize;

use crate::data::Dataset;
use crate::fit::{Evaluation, Fit};

/// The JSON object printed by `accelcal fit --json` (DESIGN.md, "Interfaces").
#[derive(Debug, Serialize)]
pub struct FitJson<'a> {
    /// Model name.
    pub model: &'static str,
    /// M, 3 rows, under the convention a = matrix (m - offset).
    pub matrix: [[f64; 3]; 3],
    /// o, in the file's unit.
    pub offset: [f64; 3],
    /// Dimensionless cost at the solution.
    pub cost: f64,
    /// Solver iterations.
    pub iterations: usize,
    /// Standard error of every parameter (null without redundancy).
    pub std_errors: BTreeMap<&'a str, Option<f64>>,
    /// |gravity| in output units.
    pub g: f64,
    /// Data-file lines the fit used.
    pub lines_used: Vec<usize>,
    /// Errors of every row before and after, in output units.
    pub evaluation: &'a Evaluation,
}

impl<'a> FitJson<'a> {
    /// The JSON view of a fit and its evaluation.
    pub fn new(fit: &'a Fit, dataset: &Dataset, evaluation: &'a Evaluation, g: f64) -> Self {
        FitJson {
            model: fit.model.name(),
            matrix: fit.matrix,
            offset: fit.offset,
            cost: fit.cost,
            iterations: fit.iterations,
            std_errors: fit.parameters.iter().map(|p| (p.name.as_str(), p.std_error)).collect(),
            g,
            lines_used: fit.rows_used.iter().map(|&i| dataset.rows[i].line).collect(),
            evaluation,
        }
    }
}

/// The fit as text for a person: parameters with standard errors, then errors before and after in mg.
pub fn human(fit: &Fit, dataset: &Dataset, evaluation: &Evaluation, g: f64) -> String {
    let mut out = String::new();
    let used = fit.rows_used.len();
    let _ = writeln!(out, "model {} ({used} of {} rows used), |g| = {g}", fit.model.name(), dataset.rows.len());
    let _ = writeln!(out, "a = M (m - o); cost {:.3e}, {} iterations", fit.cost, fit.iterations);
    for parameter in &fit.parameters {
        let error = parameter.std_error.map_or("(no redundancy)".to_owned(), |e| format!("+- {e:.2e}"));
        let _ = writeln!(out, "  {:<4} {:>16} {error}", parameter.name, number(parameter.value));
    }
    let mg = |value: f64| value / g * 1000.0;
    let _ = writeln!(out, "line   ||a|-g| mg before  after   |a-ref| mg before  after");
    for row in &evaluation.rows {
        let reference = match (row.reference_error_before, row.reference_error_after) {
            (Some(before), Some(after)) => format!("{:>17.2} {:>6.2}", mg(before), mg(after)),
            _ => format!("{:>17} {:>6}", "-", "-"),
        };
        let _ = writeln!(
            out,
            "{:>4} {:>19.2} {:>6.2} {reference}",
            row.line,
            mg(row.norm_error_before),
            mg(row.norm_error_after)
        );
    }
    let (before, after) = evaluation.worst_norm_error();
    let _ = writeln!(out, "worst ||a|-g|: {:.2} mg before, {:.2} mg after", mg(before), mg(after));
    if let Some((before, after)) = evaluation.worst_reference_error() {
        let _ = writeln!(out, "worst |a-ref|: {:.2} mg before, {:.2} mg after", mg(before), mg(after));
    }
    out
}

/// A parameter value in plain notation where that stays readable, else in scientific notation.
fn number(value: f64) -> String {
    if value == 0.0 || (1e-3..1e5).contains(&value.abs()) {
        format!("{value:+.8}")
    } else {
        format!("{value:+.7e}")
    }
}
