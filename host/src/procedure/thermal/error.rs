//! Why a thermal run stopped: each layer's own error, and a person's run stopped with its bins kept.

use std::path::PathBuf;

use super::kept::KeptBinsError;
use crate::calibration::CalibrationRecordError;
use crate::fit::thermal::ThermalFitError;
use crate::link::LinkError;
use crate::procedure::ProcedureError;

/// Why `accelcal thermal` stopped.
#[derive(Debug, thiserror::Error)]
pub enum ThermalError {
    #[error(transparent)]
    Link(#[from] LinkError),
    #[error(transparent)]
    Procedure(#[from] ProcedureError),
    #[error("cannot fit the temperature model: {0}; learn over a wider span and run again")]
    Fit(#[from] ThermalFitError),
    #[error(transparent)]
    Calibration(#[from] CalibrationRecordError),
    #[error(transparent)]
    KeptBins(#[from] KeptBinsError),
    #[error("{source}; the bins learned so far (a span of {span_c:.1} degC) are kept in {}: go on from them with `accelcal thermal --port {device} --bins {}`", .path.display(), .path.display())]
    Stopped { source: Box<ThermalError>, span_c: f64, path: PathBuf, device: String },
}
