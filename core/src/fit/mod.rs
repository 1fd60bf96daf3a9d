//! Fitting a calibration `a = M (m - o)` to a data file, by the models of DESIGN.md.

mod covariance;
pub mod drift;
mod error;
mod evaluate;
mod faces;
mod fitted;
pub mod gyro;
pub mod hysteresis;
mod influence;
mod left_out;
mod linear;
mod linearised;
mod model;
mod models;
pub mod motion;
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

use std::fmt;
use std::str::FromStr;

use crate::data::Dataset;

pub use error::FitError;
pub use evaluate::{evaluate, Evaluation, RowEvaluation};
pub use fitted::{parameters_by_name, Fit, FitOptions, Parameter, Selection};
pub use left_out::{leave_one_out_rms, with_misfit};
pub use model::{Model, RICHEST_FIRST};
use models::fit_model;
pub use prediction::{axis_angles_deg, predict, Prediction, Quadratic};
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

fn model_names() -> String {
    RICHEST_FIRST.iter().map(|m| m.name()).collect::<Vec<_>>().join(", ")
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
