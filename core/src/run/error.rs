//! Why a run stopped, each cause with what to do.

use crate::fit::FitError;
use crate::link::LinkError;

/// Why the procedure stopped; each names what to do.
#[derive(Debug, thiserror::Error)]
pub enum ProcedureError {
    #[error(transparent)]
    Link(#[from] LinkError),
    #[error("the board never came to rest at any of {wanted}; place it and run the command again")]
    NeverAtTarget { wanted: String },
    #[error(
        "the board never came to rest at a new orientation; turn it and hold it still, then run the command again"
    )]
    NeverFresh,
    #[error("the board kept moving through {attempts} captures: rest it against something firm and keep still, then run the command again")]
    KeptMoving { attempts: usize },
    #[error("the device has no active calibration to verify: calibrate or upload one first")]
    NoActiveCalibration,
    #[error("{source}; {verified}")]
    VerificationStopped { source: Box<ProcedureError>, verified: String },
    #[error(
        "the temperature spanned only {:.1} degC ({low_c:.1} to {high_c:.1} degC); a temperature model needs at least {needed_c} degC: start with the board cold (rested in a cool place or just powered on) and let it warm, or move it between a cool and a warm place", high_c - low_c
    )]
    SpanTooSmall { low_c: f64, high_c: f64, needed_c: f64 },
    #[error("the noise report {path} cannot be used ({reason}): write one with `accelcal noise RECORDING --json`")]
    NoiseReport { path: std::path::PathBuf, reason: String },
    #[error("the simulated board stopped; run the command again")]
    SimulatedBoardStopped,
    #[error(transparent)]
    Fit(#[from] FitError),
    #[error(transparent)]
    Session(#[from] crate::session::SessionError),
    #[error(transparent)]
    Calibration(crate::calibration::CalibrationRecordError),
}

impl From<crate::session::OutcomeError> for ProcedureError {
    fn from(error: crate::session::OutcomeError) -> Self {
        match error {
            crate::session::OutcomeError::Fit(e) => ProcedureError::Fit(e),
            crate::session::OutcomeError::Calibration(e) => ProcedureError::Calibration(e),
        }
    }
}
