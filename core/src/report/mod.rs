//! What a fit, a calibration and a session report: one model each, computed once, then rendered
//! as text for a person ([`text`]), as the JSON of DESIGN.md ([`json`]), and for a session as an
//! HTML page with plots ([`html`]).

pub use crate::session::Board;
pub use crate::shown::{shown, utc_minutes};

pub mod allan;
mod calibrate;
mod comparison;
mod figure;
pub mod fixture;
pub mod gyro;
pub mod html;
mod html_sections;
pub mod json;
mod plot;
mod position;
mod session;
pub mod stream;
pub mod temperature;
pub mod text;
pub mod thermal;
mod uploaded;

pub use calibrate::{CalibrateReport, ChosenJson, DriftJson, HostFitSummary, TruthJson};
pub use comparison::{ComparedModel, Comparison};
pub use figure::{axis_role, Figure, Role, Series, SeriesStyle};
pub use plot::PlotError;
pub use position::PositionResult;
pub use session::{Figures, FitSummary, SessionReport, Verdict, NOT_RECORDED};

use crate::data::Dataset;
use crate::fit::{self, Evaluation, Fit, FitError, FitOptions, ModelChoice};

/// A fit of a data file with everything its renderers show.
#[derive(Debug, Clone)]
pub struct FitReport {
    /// The fit.
    pub fit: Fit,
    /// Errors of every row before and after.
    pub evaluation: Evaluation,
    /// |gravity| in output units.
    pub g: f64,
    /// Data rows in the file.
    pub rows: usize,
    /// With `--model auto`: every model on the same rows.
    pub comparison: Option<Comparison>,
}

impl FitReport {
    /// Fits `choice` to the data set and evaluates it; for `auto`, compares every model, reusing
    /// this fit for the model it chose.
    pub fn new(dataset: &Dataset, choice: ModelChoice, options: &FitOptions) -> Result<Self, FitError> {
        Ok(FitReport::of(dataset, fit::fit(dataset, choice, options)?, choice, options))
    }

    /// The report of `fit`, made with `choice` and `options`, on the data set: evaluated at its
    /// rows and, for `auto`, compared with every model on them.
    pub fn of(dataset: &Dataset, mut fit: Fit, choice: ModelChoice, options: &FitOptions) -> Self {
        // NOTE: here, not in `fit::fit`: a run's stop rule fits after each capture and needs only the
        // parameters' figure, while a report states what a fresh orientation will meet.
        if let Ok(training) = options.training_set(dataset) {
            fit.prediction = fit::with_misfit(&fit, &training, options);
        }
        let evaluation = fit::evaluate(dataset, &fit.matrix, &fit.offset, options.g, &fit.lines_used);
        let comparison = (choice == ModelChoice::Auto).then(|| Comparison::new(dataset, options, &fit, &evaluation));
        FitReport { fit, evaluation, g: options.g, rows: dataset.rows.len(), comparison }
    }
}
