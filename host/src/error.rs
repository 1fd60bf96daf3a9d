//! The library's top error: each layer's own error, wrapped where the command line crosses it, and
//! the few refusals of the command line itself. Every message names the cause and the way out.

use std::path::PathBuf;

use crate::calibration::CalibrationRecordError;
use crate::data::DataError;
use crate::fit::{FitError, ModelChoice};
use crate::link::LinkError;
use crate::noise::input::NoiseInputError;
use crate::procedure::ProcedureError;
use crate::session::SessionError;
use crate::sim::SimError;

/// Why a command failed.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    #[error(transparent)]
    Link(#[from] LinkError),
    #[error(transparent)]
    Procedure(#[from] ProcedureError),
    #[error(transparent)]
    Session(#[from] SessionError),
    #[error(transparent)]
    Calibration(#[from] CalibrationRecordError),
    #[error(transparent)]
    Sim(#[from] SimError),
    #[error("{}: {source}", .path.display())]
    DataFile { path: PathBuf, source: DataError },
    #[error("{}: cannot fit {model}: {source}", .path.display())]
    CannotFit { path: PathBuf, model: ModelChoice, source: FitError },
    #[error(transparent)]
    Fit(#[from] FitError),
    #[error("--g must be a positive number, got {g}")]
    BadGravity { g: f64 },
    #[error("which device? give --port PATH (see `accelcal ports`) or --sim")]
    WhichDevice,
    #[error("the device has no calibration to download: calibrate or upload one first")]
    NothingToDownload,
    #[error(transparent)]
    NoiseInput(#[from] NoiseInputError),
    #[error("cannot write {}: {source}; check the folder exists and is writable", .path.display())]
    WriteFile { path: PathBuf, source: std::io::Error },
    #[error("cannot read {}: {source}; check the path", .path.display())]
    ReadFile { path: PathBuf, source: std::io::Error },
}
