//! The library's top error: each layer's own error, wrapped where the command line crosses it, and
//! the few refusals of the command line itself. Every message names the cause and the way out.

use std::path::PathBuf;

use crate::calibration::CalibrationRecordError;
use crate::data::DataError;
use crate::fit::{FitError, ModelChoice};
use crate::link::LinkError;
use crate::noise::input::NoiseInputError;
use crate::procedure::ProcedureError;
use crate::report::PlotError;
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
    #[error(transparent)]
    Emulator(#[from] crate::sim::EmulatorError),
    #[error(transparent)]
    Web(#[from] crate::web::WebError),
    #[error("{}: {source}", .path.display())]
    DataFile { path: PathBuf, source: DataError },
    #[error("{}: cannot fit {model}: {source}", .path.display())]
    CannotFit { path: PathBuf, model: ModelChoice, source: FitError },
    #[error(transparent)]
    Fit(#[from] FitError),
    // NOTE: the core's error, named where it lives: through the host's `stream` (which uses this
    // error to run a stream's session) it would read as a circle between the two.
    #[error("{}: read as a sensor's stream: {source}", .path.display())]
    Stream { path: PathBuf, source: accelcal_core::stream::StreamError },
    #[error("{}: read as a sensor's stream, its still periods cannot be fitted: {source}", .path.display())]
    StreamFit { path: PathBuf, source: crate::report::stream::StreamFitError },
    #[error("{}: cannot report this session: {source}", .path.display())]
    CannotReport { path: PathBuf, source: FitError },
    #[error(
        "{}: no certificate: its verification found {verified_mg:.3} mg at fresh orientations (without its {floor_mg:.3} mg of noise), beyond the U = {predicted_mg:.3} mg the certificate would state; let the board warm up, rest it firmly and calibrate again",
        .path.display()
    )]
    Contradicted { path: PathBuf, verified_mg: f64, floor_mg: f64, predicted_mg: f64 },
    #[error(transparent)]
    Plot(#[from] PlotError),
    #[error(transparent)]
    Certificate(#[from] crate::certificate::SealError),
    #[error(transparent)]
    Lot(#[from] crate::lot::LotError),
    #[error("{} already exists: {other}, or add --overwrite to replace it", .path.display())]
    OutputExists { path: PathBuf, other: &'static str },
    #[error("--g must be a positive number, got {g}")]
    BadGravity { g: f64 },
    #[error(
        "{}: the references have a size of {size:.4}, gravity's in m/s^2, where --g is {g}: give --g 9.81 (or your \
         local g in m/s^2) so that the fit compares | |a| - g | in their unit",
        .path.display()
    )]
    ReferencesInOtherUnit { path: PathBuf, size: f64, g: f64 },
    #[error("{source}; {} so far {} kept in {}: continue with `accelcal calibrate {device} --resume {}`", count(*.captures, "capture"), if *.captures == 1 { "is" } else { "are" }, .path.display(), .path.display())]
    Stopped { source: Box<ProcedureError>, captures: usize, path: PathBuf, device: String },
    #[error("{source}; the verification is not kept: {} holds the captures and the calibration uploaded to the board; check it again with `accelcal calibrate {device} --resume {}`", .path.display(), .path.display())]
    VerificationNotKept { source: Box<SessionError>, path: PathBuf, device: String },
    #[error("{source}; the calibration is already uploaded and saved on the board: {check_later}")]
    AfterUpload { source: Box<ProcedureError>, check_later: String },
    #[error("{source}; verifying changes nothing on the board: its calibration is as it was")]
    VerifyStopped { source: Box<ProcedureError> },
    #[error(
        "the calibration uploaded and saved misses --target-mg by more than its noise ({line}); it stays on the board"
    )]
    TargetMissed { line: String },
    #[error("several boards on one fixture are uploaded without asking (one answer would hold up them all): add --yes, or calibrate one board at a time to see each fit before its upload")]
    FixtureNeedsYes,
    #[error("a session of several boards cannot be resumed as one: resume each board's session on its own with `accelcal calibrate --port PORT --resume SESSION`")]
    FixtureCannotResume,
    #[error(
        "{failed}; {calibrated} of {boards} boards calibrated: fix the named cause and calibrate the others again"
    )]
    BoardsFailed { failed: String, calibrated: usize, boards: usize },
    #[error("--sim-pull names board {board}, but the fixture holds {boards}: give a board from 1 to {boards}")]
    NoSuchBoard { board: usize, boards: usize },
    #[error("--json cannot ask whether to upload the calibration: add --yes to upload and save it, or leave out --json to be asked")]
    JsonCannotAsk,
    #[error("{port} prints its own stream, which names no board the lot could key its certificate by: give the board's serial or label with --serial LABEL, or leave out --lot")]
    StreamLotNeedsSerial { port: String },
    #[error("--serial is for a board that prints its own stream; this board runs accelcal's firmware and reports its own serial {reported}: leave out --serial")]
    SerialOfItsOwn { reported: String },
    #[error(transparent)]
    SelfTest(#[from] crate::selftest::SelfTestError),
    #[error(transparent)]
    FamilyCheck(#[from] crate::part::offsets::OffsetCheckError),
    #[error(transparent)]
    SelfTestHistory(#[from] crate::selftest::history::HistoryError),
    #[error("the self-test failed: an axis' response is outside +-{} % of its factory trim (see above); the part is damaged or not what it claims", shared::selftest::ACCELCAL_BAND_PERCENT)]
    SelfTestFailed,
    #[error("repeat needs a power cycle between the sessions, which accelcal cannot do to a board on a port yet: use --sim, or power-cycle the board by hand between `accelcal calibrate --lot LOT` runs and read the spread with `accelcal lot board LOT SERIAL`")]
    RepeatNeedsSim,
    #[error("the device has no calibration to download: calibrate or upload one first")]
    NothingToDownload,
    #[error("the board holds no active calibration, so --calibrated would print its raw readings: calibrate it first (accelcal calibrate), upload one (accelcal upload), or stream without --calibrated")]
    NothingToApply,
    #[error(transparent)]
    Thermal(#[from] crate::procedure::thermal::error::ThermalError),
    #[error(transparent)]
    Export(#[from] crate::export::ExportError),
    #[error(transparent)]
    NoiseInput(#[from] NoiseInputError),
    #[error(transparent)]
    Recording(#[from] crate::recording::RecordingError),
    #[error("the board ran at {achieved_hz} Hz, not the {wanted_hz} Hz asked for; choose a rate that divides 1000 Hz")]
    RateNotAchieved { wanted_hz: u16, achieved_hz: u16 },
    #[error("{source}; the {written} samples before it are kept in {} (np.load reads them)", .path.display())]
    RecordingCut { written: u64, path: PathBuf, source: LinkError },
    #[error("cannot write {}: {source}; check the folder exists and is writable", .path.display())]
    WriteFile { path: PathBuf, source: std::io::Error },
    #[error("cannot read {}: {source}; check the path", .path.display())]
    ReadFile { path: PathBuf, source: std::io::Error },
    #[error("{} cannot go into the report: {reason}", .path.display())]
    ReportInput { path: PathBuf, reason: String },
}

impl From<crate::session::OutcomeError> for Error {
    fn from(error: crate::session::OutcomeError) -> Self {
        match error {
            crate::session::OutcomeError::Fit(e) => Error::Fit(e),
            crate::session::OutcomeError::Calibration(e) => Error::Calibration(e),
        }
    }
}

/// The exit status of a calibration that was uploaded and saved but missed its target (documented).
pub const TARGET_MISSED_EXIT: u8 = 2;

impl Error {
    /// The process's exit status for this error: [`TARGET_MISSED_EXIT`] for a missed target or a failed
    /// self-test (done, but its check failed), else 1.
    pub fn exit_code(&self) -> u8 {
        match self {
            Error::TargetMissed { .. } | Error::SelfTestFailed => TARGET_MISSED_EXIT,
            _ => 1,
        }
    }

    /// A data file refused: a file that cannot be read is named once (the reader's message already
    /// holds the path), a bad one with the path before the line and cause.
    pub fn data_file(path: &std::path::Path, source: DataError) -> Self {
        match source {
            DataError::Io { source, .. } => Error::ReadFile { path: path.to_owned(), source },
            source => Error::DataFile { path: path.to_owned(), source },
        }
    }
}

/// `n` and the noun, plural unless there is one.
fn count(n: usize, noun: &str) -> String {
    if n == 1 {
        format!("1 {noun}")
    } else {
        format!("{n} {noun}s")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_data_file_that_cannot_be_read_names_its_path_once() {
        let path = std::path::Path::new("/tmp/accelcal-missing.csv");
        let source = std::io::Error::from(std::io::ErrorKind::NotFound);
        let error = Error::data_file(path, DataError::Io { path: path.display().to_string(), source });
        let text = error.to_string();
        assert_eq!(text.matches("/tmp/accelcal-missing.csv").count(), 1, "{text}");
        assert!(text.starts_with("cannot read /tmp/accelcal-missing.csv: "), "{text}");
        assert!(text.ends_with("; check the path"), "{text}");
    }

    #[test]
    fn counts_are_plural_unless_there_is_one() {
        assert_eq!(
            (count(1, "capture"), count(2, "capture"), count(0, "capture")),
            ("1 capture".into(), "2 captures".into(), "0 captures".into())
        );
    }

    #[test]
    fn a_missed_target_exits_2_and_other_errors_1() {
        let missed = accelcal_core::session::Verification::example(1.06, 0.1).against(Some(0.2));
        assert!(missed.missed, "{missed:?}");
        assert_eq!(Error::TargetMissed { line: missed.line }.exit_code(), 2);
        assert_eq!(Error::FixtureNeedsYes.exit_code(), 1);
    }
}
