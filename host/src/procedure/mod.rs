//! The guided run on a port: the core's run (`accelcal_core::run`), each step blocking on the
//! board's [`Client`]; and what only a host has: several boards on one fixture turned by threads
//! (where their threads meet, the core's `run::fixture` held under a lock: [`fixture`]; each board's
//! session on its own thread: [`together`]), the thermal run. The simulated hand and session are the
//! core's, reached through `sim`.

pub mod fixture;
pub mod thermal;
pub mod together;

use std::time::Duration;

use embassy_futures::block_on;

pub use accelcal_core::run::*;
pub use fixture::{Fixture, Seat, TimedMember};

use crate::link::{Client, Port};
use crate::session::{Session, SessionError};

// NOTE: the core's steps are `async` over a link whose port the host owns; a port here blocks, so each
// step's future is ready as soon as it is polled, and `block_on` only unwraps it.

/// Captures every target, in whatever order the board arrives at them (`run::collect`).
pub fn collect<P: Port>(
    client: &mut Client<P>,
    hand: &mut dyn Hand,
    targets: &[Orientation],
    options: &CollectOptions,
    feedback: &mut dyn Feedback,
) -> Result<Session, ProcedureError> {
    block_on(accelcal_core::run::collect(client.link(), hand, targets, options, feedback))
}

/// Captures the targets `session` lacks into it, keeping it after every capture (`run::collect_into`).
pub fn collect_into<P: Port>(
    client: &mut Client<P>,
    turning: Turning<'_>,
    targets: &[Orientation],
    options: &CollectOptions,
    feedback: &mut dyn Feedback,
    session: &mut Session,
    keep: &mut dyn FnMut(&Session) -> Result<(), SessionError>,
) -> Result<(), ProcedureError> {
    block_on(accelcal_core::run::collect_into(client.link(), turning, targets, options, feedback, session, keep))
}

/// An adaptive session's captures (`run::collect_adaptive`).
pub fn collect_adaptive<P: Port>(
    client: &mut Client<P>,
    turning: Turning<'_>,
    targets: &[Orientation],
    options: &AdaptiveOptions,
    feedback: &mut dyn Feedback,
    session: &mut Session,
    keep: &mut dyn FnMut(&Session) -> Result<(), SessionError>,
) -> Result<Collected, ProcedureError> {
    block_on(accelcal_core::run::collect_adaptive(client.link(), turning, targets, options, feedback, session, keep))
}

/// The board's active calibration checked at fresh orientations (`run::verify`).
pub fn verify<P: Port>(
    client: &mut Client<P>,
    hand: &mut dyn Hand,
    positions: usize,
    wait_limit: Option<Duration>,
    feedback: &mut dyn Feedback,
) -> Result<Verification, ProcedureError> {
    block_on(accelcal_core::run::verify(client.link(), hand, positions, wait_limit, feedback))
}

/// As [`verify`], the fresh orientations kept clear of `calibrated` (`run::verify_clear_of`).
pub fn verify_clear_of<P: Port>(
    client: &mut Client<P>,
    hand: &mut dyn Hand,
    positions: usize,
    wait_limit: Option<Duration>,
    feedback: &mut dyn Feedback,
    calibrated: &[[f64; 3]],
) -> Result<Verification, ProcedureError> {
    block_on(accelcal_core::run::verify_clear_of(client.link(), hand, positions, wait_limit, feedback, calibrated))
}

/// As [`verify_clear_of`], each capture of `length` (`run::verify_with`).
pub fn verify_with<P: Port>(
    client: &mut Client<P>,
    hand: &mut dyn Hand,
    positions: usize,
    wait_limit: Option<Duration>,
    feedback: &mut dyn Feedback,
    calibrated: &[[f64; 3]],
    length: stop_rule::CaptureLength,
) -> Result<Verification, ProcedureError> {
    let link = client.link();
    block_on(accelcal_core::run::verify_with(link, hand, positions, wait_limit, feedback, calibrated, length))
}

/// The gyro's calibration checked on one quarter turn (`run::check_turn`).
pub fn check_turn<P: Port>(
    client: &mut Client<P>,
    hand: &mut dyn Hand,
    rate_hz: u16,
    fit: Option<&crate::fit::gyro::GyroFit>,
    feedback: &mut dyn Feedback,
) -> Result<Result<TurnCheck, String>, ProcedureError> {
    block_on(accelcal_core::run::check_turn(client.link(), hand, rate_hz, fit, feedback))
}
