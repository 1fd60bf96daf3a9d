//! The guided procedure: ask for each wanted orientation, see when the board is there and still,
//! capture, and verify a calibration at fresh orientations. Who turns the board is a [`Hand`]: a
//! person following instructions, or the tool's own hand on the simulated board.

mod adaptive;
mod collect;
pub use accelcal_core::run::drift;
mod feedback;
mod fixture;
mod gyro_check;
mod hand;
mod moves;
mod simulated_hand;
mod simulated_session;
pub mod stop_rule;
pub mod thermal;
mod turns;
mod verify;
mod wait;

use std::time::Duration;

pub use crate::orientation::{corners, faces, quick_set, Orientation};
pub use crate::session::{TargetVerdict, TurnCheck};
pub use adaptive::{collect_adaptive, AdaptiveOptions, BoardClock, Collected};
pub use collect::{collect, collect_into};
#[cfg(test)]
pub(crate) use feedback::Told;
pub use feedback::{Feedback, Silent};
pub use fixture::{Fixture, FixtureHand, Pull, Seat, SimulatedMember};
pub use gyro_check::check_turn;
pub use hand::{Hand, PersonHand};
pub use moves::{Moves, RecordedMove, Turning};
pub use simulated_hand::SimulatedHand;
pub use simulated_session::SimulatedSession;
pub use turns::{fit_moves, turn_summaries, turns_of};
pub use verify::{verify, verify_clear_of, verify_with, Verification, VERIFY_SECONDS};

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

/// How the captures of [`collect`] run.
#[derive(Debug, Clone)]
pub struct CollectOptions {
    /// Capture length, in seconds.
    pub seconds: u8,
    /// Give up waiting for a position after this long (`None`: wait for the person).
    pub wait_limit: Option<Duration>,
}

/// Capture length of a quick calibration, in seconds: the shortest the board takes.
///
/// NOTE: a board just powered on warms, and its offsets drift with it (about 0.03 mg/s, simulated
/// sensor); the shorter session drifts less, and a 5 s mean still carries only 0.13 mg of noise per
/// axis (400 ug/sqrt(Hz), Product Specification 6.2). Measured (tests/quick_mode.rs, 20 seeds):
/// 5 s captures 0.320 mg rms true error, 68 s on the board; 10 s captures 0.454 mg, 118 s (with a hand
/// that put the board down at once; turning at a person's pace, 5 s: 0.361 mg, 82 s).
pub const QUICK_CAPTURE_SECONDS: u8 = shared::protocol::MIN_CAPTURE_SECONDS;

/// The capture length when the user does not choose one, in seconds.
pub fn capture_seconds(quick: bool) -> u8 {
    if quick {
        QUICK_CAPTURE_SECONDS
    } else {
        shared::protocol::DEFAULT_CAPTURE_SECONDS
    }
}

/// The orientations a calibration asks for: the six faces and the eight corners, or for a quick one
/// the ten of [`quick_set`].
pub fn targets(quick: bool) -> Vec<Orientation> {
    if quick {
        quick_set()
    } else {
        [faces(), corners()].concat()
    }
}
