//! Every model fitted to the same rows, and the misalignment the 9- and 12-parameter fits reveal.

use crate::fit::Model;
use serde::Serialize;

use crate::data::Dataset;
use crate::fit::{self, misalignment_deg, Evaluation, Fit, FitError, FitOptions, ModelChoice, RICHEST_FIRST};

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

/// Every model fitted to the same rows, richest first.
#[derive(Debug, Clone, Serialize)]
pub struct Comparison {
    /// Richest first.
    pub models: Vec<ComparedModel>,
    /// Rotation between the best 12-parameter fit and `ortho9`, in degrees: an estimate of how far
    /// the known orientations were misplaced.
    pub misalignment_deg: Option<f64>,
}

impl Comparison {
    /// Fits every model but the one already fitted (`chosen`, with its `evaluation`) to the rows
    /// `options` selects.
    pub fn new(dataset: &Dataset, options: &FitOptions, chosen: &Fit, evaluation: &Evaluation) -> Self {
        let fits: Vec<(Model, Result<Fit, FitError>)> = RICHEST_FIRST
            .into_iter()
            .map(|model| {
                let result = if model == chosen.model {
                    Ok(chosen.clone())
                } else {
                    fit::fit(dataset, ModelChoice::Only(model), options)
                };
                (model, result)
            })
            .collect();
        let models =
            fits.iter().map(|(model, result)| compare(dataset, options, chosen, evaluation, *model, result)).collect();
        Comparison { models, misalignment_deg: misalignment(&fits) }
    }
}

/// One model's line: its cost and errors, or why it was refused.
fn compare(
    dataset: &Dataset,
    options: &FitOptions,
    chosen: &Fit,
    chosen_evaluation: &Evaluation,
    model: Model,
    result: &Result<Fit, FitError>,
) -> ComparedModel {
    let fit = match result {
        Ok(fit) => fit,
        Err(error) => {
            let refused = Some(error.to_string());
            let model = model.name();
            return ComparedModel { model, cost: None, training_rms_mg: None, test_rms_mg: None, refused };
        }
    };
    let evaluation = if model == chosen.model {
        chosen_evaluation.clone()
    } else {
        fit::evaluate(dataset, &fit.matrix, &fit.offset, options.g, &fit.lines_used)
    };
    let mg = |value: f64| value / options.g * 1000.0;
    ComparedModel {
        model: model.name(),
        cost: Some(fit.cost),
        training_rms_mg: evaluation.rms_norm_error(true).map(mg),
        test_rms_mg: evaluation.rms_norm_error(false).map(mg),
        refused: None,
    }
}

/// The rotation between the best 12-parameter fit and `ortho9`, when both fitted.
fn misalignment(fits: &[(Model, Result<Fit, FitError>)]) -> Option<f64> {
    let fitted = |wanted: Model| fits.iter().find(|(m, _)| *m == wanted).and_then(|(_, r)| r.as_ref().ok());
    let full = fitted(Model::ReferenceNorm12).or_else(|| fitted(Model::Linear12));
    full.zip(fitted(Model::Ortho9)).and_then(|(f, t)| misalignment_deg(&f.matrix, &t.matrix))
}
