//! Why a session file could not be written, read or resumed.

use std::path::PathBuf;

/// Why a session file could not be written or read.
#[derive(Debug, thiserror::Error)]
pub enum SessionError {
    #[error("cannot write {path}: {source}; give the path of a file (not a directory) in a directory that exists and is writable")]
    Write { path: PathBuf, source: std::io::Error },
    #[error("cannot read {path}: {source}; give the path of a session written by calibrate or capture")]
    Read { path: PathBuf, source: std::io::Error },
    #[error("{path} is not a session file ({reason}); give the .json file written by calibrate or capture")]
    NotASession { path: PathBuf, reason: String },
    #[error("{path} is not a session but {what}; give the session's .json file written by calibrate or capture")]
    OtherFile { path: PathBuf, what: &'static str },
    #[error("{path} is being written by another run of accelcal ({holder}); wait for it to end, or give another --session name")]
    Busy { path: PathBuf, holder: String },
    #[error("{path} already holds a session; continue it with `--resume {path}`, or give another --session name")]
    Exists { path: PathBuf },
    #[error("{path} is not a session of a board's own stream; resume it with the board it was captured on, or start a new one without --resume")]
    NotAStream { path: PathBuf },
    #[error(
        "{path} is a session of a board's own stream (its sketch's lines, read from {port}), which this accelcal \
         board cannot go on with: resume it where that board prints, `accelcal calibrate --port {port} --resume {path}`, \
         or start a new calibration without --resume"
    )]
    StreamOnBoard { path: PathBuf, port: String },
    #[error("{path} records no board; only a session written by calibrate can be resumed")]
    NoBoard { path: PathBuf },
    #[error("{path} was captured on another board (serial {session}), this one is {board}: connect that board, or start a new calibration")]
    OtherBoard { path: PathBuf, session: String, board: String },
    #[error("{path} was captured at {session}, the board is set to {board}: captures at another setting do not fit together; start a new calibration")]
    OtherSetting { path: PathBuf, session: String, board: String },
}
