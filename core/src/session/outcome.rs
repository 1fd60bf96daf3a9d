//! What a session yields: the one place that turns a session's captures into its fit, its drift and
//! its calibration, as `calibrate` uploads it and as the report shows it.

use shared::calibration::TemperatureModel;
use shared::protocol::SensorConfig;
use shared::Calibration;

use super::{Session, SessionKind};
use crate::calibration::{self, CalibrationRecordError};
use crate::data::Dataset;
use crate::fit::drift::{self, Drift};
use crate::fit::{self, Fit, FitError, FitOptions, Model, ModelChoice};

/// Why a session yields no calibration.
#[derive(Debug, thiserror::Error)]
pub enum OutcomeError {
    #[error(transparent)]
    Fit(#[from] FitError),
    #[error(transparent)]
    Calibration(#[from] CalibrationRecordError),
}

/// The captures as the calibration is fitted to them, and the drift taken out of them.
#[derive(Debug, Clone, PartialEq)]
pub struct Fitted {
    /// The model the calibration is fitted with.
    pub model: ModelChoice,
    /// The offset drift with the temperature fitted with an adaptive session, when the board warmed
    /// and had no learned temperature model.
    pub drift: Option<Drift>,
    /// The learned temperature model an adaptive session kept (`Session::learned`'s).
    pub learned: Option<TemperatureModel>,
    /// The captures in g, an adaptive session's corrected for `drift` to their mean temperature, or
    /// by the learned model to its reference temperature.
    pub captures: Dataset,
}

/// A session's fit, drift and calibration.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// The host's fit of the captures as fitted.
    pub fit: Fit,
    /// The captures as fitted, with the drift and the model.
    pub fitted: Fitted,
    /// The device calibration: the fit, with the drift as a temperature model when there is one.
    pub calibration: Calibration,
}

impl Session {
    /// The model a session's calibration is fitted with: for a `--chip-fit` session the chip's own,
    /// `ortho9` (the six-position closed form for a quick session of the six faces alone, as taken
    /// before the chip fitted `ortho9`), `ortho9` for an adaptive one, the host's choice otherwise.
    pub fn model(&self) -> ModelChoice {
        match self.kind {
            SessionKind::Quick if self.captures.len() < shared::ortho9::MIN_READINGS => {
                ModelChoice::Only(Model::SixPosition)
            }
            SessionKind::Quick | SessionKind::Adaptive | SessionKind::Stream => ModelChoice::Only(Model::Ortho9),
            SessionKind::Fixed => ModelChoice::Auto,
        }
    }

    /// The captures as the calibration is fitted to them: an adaptive session's corrected by the
    /// board's learned temperature model when it has one (to the model's reference temperature), else
    /// for the offset drift fitted with them (to their mean temperature); any other's as taken.
    pub fn fitted(&self) -> Fitted {
        let (captures, model) = (self.dataset(), self.model());
        if self.kind != SessionKind::Adaptive {
            return Fitted { model, drift: None, learned: None, captures };
        }
        if let Some(learned) = &self.learned {
            let captures = drift::learned::at_reference(&captures, learned);
            return Fitted { model, drift: None, learned: learned.temperature, captures };
        }
        let drift = mutant!("adaptive-drift-unfitted", drift::fitted(&captures), None);
        let captures = drift::at_mean_temperature(&captures, drift.as_ref());
        Fitted { model, drift, learned: None, captures }
    }

    /// The host's fit of the session, with the captures it was fitted to.
    pub fn fit(&self) -> Result<(Fit, Fitted), FitError> {
        let fitted = self.fitted();
        Ok((fit::fit(&fitted.captures, fitted.model, &FitOptions::default())?, fitted))
    }

    /// The session's fit, drift and the device calibration made of them for a board set to `config`.
    pub fn outcome(&self, config: SensorConfig) -> Result<Outcome, OutcomeError> {
        let (fit, fitted) = self.fit()?;
        let calibration = calibration::from_fit(&fit, &fitted.captures, config)?;
        let calibration = match (&fitted.drift, fitted.learned) {
            (Some(d), _) => {
                calibration::with_offset_drift(&calibration, drift::mean_temp_c(&fitted.captures), d.slope_g_per_c)
            }
            (None, Some(model)) => Calibration { temperature: Some(model), ..calibration },
            (None, None) => calibration,
        };
        Ok(Outcome { fit, fitted, calibration })
    }
}
