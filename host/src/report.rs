//! What `accelcal fit` prints: a table for a person, or the JSON object of DESIGN.md.

use std::collections::BTreeMap;
use std::fmt::Write;

use serde::Serialize;

use crate::data::Dataset;
use crate::fit::{self, misalignment_deg, Evaluation, Fit, FitOptions, Model, NoiseTest};

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
    /// Solver iterations (residual evaluations).
    pub iterations: usize,
    /// Standard error of every parameter (null without redundancy).
    pub std_errors: BTreeMap<&'a str, Option<f64>>,
    /// Every parameter's value, by name.
    pub parameters: BTreeMap<&'a str, f64>,
    /// |gravity| in output units.
    pub g: f64,
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
    /// The JSON view of a fit, its evaluation and, for `auto`, the comparison.
    pub fn new(fit: &'a Fit, evaluation: &'a Evaluation, g: f64, comparison: Option<&'a Comparison>) -> Self {
        FitJson {
            model: fit.model.name(),
            matrix: fit.matrix,
            offset: fit.offset,
            cost: fit.cost,
            iterations: fit.iterations,
            std_errors: fit.parameters.iter().map(|p| (p.name.as_str(), p.std_error)).collect(),
            parameters: fit.parameters.iter().map(|p| (p.name.as_str(), p.value)).collect(),
            g,
            lines_used: &fit.lines_used,
            noise_test: fit.noise_test.as_ref(),
            warnings: &fit.warnings,
            evaluation,
            comparison,
        }
    }
}

/// One model of the comparison.
#[derive(Debug, Clone, Serialize)]
pub struct ComparedModel {
    /// Model name.
    pub model: &'static str,
    /// Cost at the solution; `None` when the data does not support the model.
    pub cost: Option<f64>,
    /// RMS of | |a| - g | over the training rows, in mg.
    pub training_rms_mg: Option<f64>,
    /// RMS of | |a| - g | over the held-out rows, in mg.
    pub test_rms_mg: Option<f64>,
    /// Why the model could not be fitted.
    pub refused: Option<String>,
}

/// Every model fitted to the same rows, and the misalignment the 9- and 12-parameter fits reveal.
#[derive(Debug, Clone, Serialize)]
pub struct Comparison {
    /// Richest first.
    pub models: Vec<ComparedModel>,
    /// Rotation between the best 12-parameter fit and `ortho9`, in degrees: an estimate of how far
    /// the known orientations were misplaced.
    pub misalignment_deg: Option<f64>,
}

impl Comparison {
    /// Fits every model to the rows `options` selects.
    pub fn new(dataset: &Dataset, options: &FitOptions) -> Self {
        let fits = fit::fit_all(dataset, options);
        let mg = |value: f64| value / options.g * 1000.0;
        let models = fits
            .iter()
            .map(|(model, result)| match result {
                Ok(fit) => {
                    let evaluation = fit::evaluate(dataset, &fit.matrix, &fit.offset, options.g, &fit.lines_used);
                    ComparedModel {
                        model: model.name(),
                        cost: Some(fit.cost),
                        training_rms_mg: evaluation.rms_norm_error(true).map(mg),
                        test_rms_mg: evaluation.rms_norm_error(false).map(mg),
                        refused: None,
                    }
                }
                Err(error) => ComparedModel {
                    model: model.name(),
                    cost: None,
                    training_rms_mg: None,
                    test_rms_mg: None,
                    refused: Some(error.to_string()),
                },
            })
            .collect();
        let fitted =
            |wanted: Model| fits.iter().find(|(m, r)| *m == wanted && r.is_ok()).and_then(|(_, r)| r.as_ref().ok());
        let full = fitted(Model::ReferenceNorm12).or_else(|| fitted(Model::Linear12));
        let misalignment_deg =
            full.zip(fitted(Model::Ortho9)).and_then(|(f, t)| misalignment_deg(&f.matrix, &t.matrix));
        Comparison { models, misalignment_deg }
    }

    /// The comparison as text for a person.
    pub fn human(&self) -> String {
        let mut out =
            String::from("model comparison (same rows):\n  model             cost        ||a|-g| rms mg train  test\n");
        let cell = |v: Option<f64>, digits: usize| v.map_or("-".to_owned(), |v| format!("{v:.digits$}"));
        for m in &self.models {
            match &m.refused {
                Some(reason) => {
                    let _ = writeln!(out, "  {:<17} not supported: {reason}", m.model);
                }
                None => {
                    let cost = m.cost.map_or("-".to_owned(), |c| format!("{c:.3e}"));
                    let (train, test) = (cell(m.training_rms_mg, 3), cell(m.test_rms_mg, 3));
                    let _ = writeln!(out, "  {:<17} {cost:<11} {train:>20} {test:>6}", m.model);
                }
            }
        }
        if let Some(angle) = self.misalignment_deg {
            let _ = writeln!(out, "placement misalignment (12- vs 9-parameter fit): {angle:.2} degrees");
        }
        out
    }
}

/// The fit as text for a person: parameters with standard errors, then errors before and after in mg.
pub fn human(fit: &Fit, dataset: &Dataset, evaluation: &Evaluation, g: f64) -> String {
    let mut out = String::new();
    let used = fit.lines_used.len();
    let _ = writeln!(out, "model {} ({used} of {} rows used), |g| = {g}", fit.model.name(), dataset.rows.len());
    let _ = writeln!(out, "a = M (m - o); cost {:.3e}, {} iterations", fit.cost, fit.iterations);
    for parameter in &fit.parameters {
        let error = parameter.std_error.map_or("(no redundancy)".to_owned(), |e| format!("+- {e:.2e}"));
        let _ = writeln!(out, "  {:<4} {:>16} {error}", parameter.name, number(parameter.value));
    }
    if let Some(test) = &fit.noise_test {
        let verdict = if test.passed { "consistent with" } else { "larger than" };
        let _ = writeln!(
            out,
            "residuals {verdict} the capture noise: chi-square {:.1} on {} degrees of freedom, p = {:.3}",
            test.chi_square, test.degrees_of_freedom, test.p_value
        );
    }
    for warning in &fit.warnings {
        let _ = writeln!(out, "warning: {warning}");
    }
    write_rows(&mut out, evaluation, g);
    out
}

fn write_rows(out: &mut String, evaluation: &Evaluation, g: f64) {
    let mg = |value: f64| value / g * 1000.0;
    let angles = evaluation.rows.iter().any(|r| r.inclination_error_deg.is_some());
    let _ = write!(out, "line  set    ||a|-g| mg before   after   |a-ref| mg before   after");
    let _ = writeln!(out, "{}", if angles { "  incl err deg  tf err deg" } else { "" });
    let cell = |v: Option<f64>, width: usize, digits: usize| {
        v.map_or(format!("{:>width$}", "-"), |v| format!("{v:>width$.digits$}"))
    };
    for row in &evaluation.rows {
        let set = if row.training { "train" } else { "test" };
        let _ = write!(
            out,
            "{:>4}  {set:<5} {:>17.2} {:>7.2} {} {}",
            row.line,
            mg(row.norm_error_before),
            mg(row.norm_error_after),
            cell(row.reference_error_before.map(mg), 17, 2),
            cell(row.reference_error_after.map(mg), 7, 2)
        );
        if angles {
            let _ = write!(out, " {} {}", cell(row.inclination_error_deg, 13, 3), cell(row.toolface_error_deg, 11, 3));
        }
        out.push('\n');
    }
    let (before, after) = evaluation.worst_norm_error();
    let _ = writeln!(out, "worst ||a|-g|: {:.2} mg before, {:.2} mg after", mg(before), mg(after));
    if let Some((before, after)) = evaluation.worst_reference_error() {
        let _ = writeln!(out, "worst |a-ref|: {:.2} mg before, {:.2} mg after", mg(before), mg(after));
    }
}

/// A parameter value in plain notation where that stays readable, else in scientific notation.
fn number(value: f64) -> String {
    if value == 0.0 || (1e-3..1e5).contains(&value.abs()) {
        format!("{value:+.8}")
    } else {
        format!("{value:+.7e}")
    }
}
