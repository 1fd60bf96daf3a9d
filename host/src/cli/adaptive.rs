//! `calibrate`'s adaptive session (the default for a full calibration): positions in
//! drift-cancelling order, each averaged until its mean is known well enough, no more positions once
//! the fit predicts the target, the drift the temperature caused fitted and said, verification as
//! long as the target needs.

use shared::protocol::{CalibrationSlot, SensorConfig};
use shared::Calibration;

use super::args::CalibrateArgs;
use super::device::Opened;
use super::length::{ADAPTIVE_VERIFY_POSITIONS, FIXED_VERIFY_POSITIONS};
use crate::error::Error;
use crate::fit::drift;
use crate::limits::DRIFT_MIN_CHANGE_C;
use crate::link::{Client, Port};
use crate::procedure::stop_rule::CaptureLength;
use crate::procedure::{self, AdaptiveOptions, Feedback, Turning, VERIFY_SECONDS};
use crate::session::{Outcome, Session, SessionError, SessionKind};

/// What a new session is: quick (`--quick`), of fixed-length captures (`--seconds`), or adaptive.
/// A resumed session keeps what it was begun as, so that its collection, its fit and its report agree.
pub(super) fn begun_as(args: &CalibrateArgs) -> SessionKind {
    match (args.quick, args.seconds) {
        (true, _) => SessionKind::Quick,
        (false, Some(_)) => SessionKind::Fixed,
        (false, None) => SessionKind::Adaptive,
    }
}

/// What a resumed session makes of `--quick` and `--seconds` given differently from when it was
/// begun, in words: it goes on as it was begun (its captures, fit and report must agree).
pub(super) fn resumed_as_begun(args: &CalibrateArgs, session: &Session) -> Vec<String> {
    let kind = |quick: bool| if quick { "a quick calibration" } else { "a full calibration" };
    let (asked_quick, begun_quick) = (args.quick, session.kind == SessionKind::Quick);
    let mut lines = Vec::new();
    if asked_quick != begun_quick {
        lines.push(format!(
            "this session was begun as {}; it goes on as one ({} is not used: start a new session for the other)",
            kind(begun_quick),
            if asked_quick { "--quick" } else { "leaving out --quick" }
        ));
    }
    if let (SessionKind::Adaptive, Some(seconds)) = (session.kind, args.seconds) {
        lines.push(format!(
            "this session was begun adaptive (each position captured until its mean is known); it goes on so and \
             --seconds {seconds} is not used (start a new session for captures of a fixed length)"
        ));
    }
    lines
}

/// Collects an adaptive session; the board's clock at its first capture.
pub(super) fn collect(
    args: &CalibrateArgs,
    opened: &mut Opened,
    turning: Turning<'_>,
    wait_limit: Option<std::time::Duration>,
    session: &mut Session,
    keep: &mut dyn FnMut(&Session) -> Result<(), SessionError>,
    feedback: &mut dyn Feedback,
) -> Result<Option<f64>, procedure::ProcedureError> {
    let rule = args.length.rule(opened.connection.info.config.sample_rate_hz)?;
    let options = AdaptiveOptions { rule, wait_limit, clock: Some(opened.clock()) };
    let client = &mut opened.connection.client;
    let targets = procedure::targets(false);
    let collected = procedure::collect_adaptive(client, turning, &targets, &options, feedback, session, keep)?;
    Ok(collected.first_capture_s)
}

/// The calibration of a session, with what the temperature did during an adaptive one said.
pub(super) fn outcome(session: &Session, config: SensorConfig, feedback: &mut dyn Feedback) -> Result<Outcome, Error> {
    let outcome = session.outcome(config)?;
    if session.kind != SessionKind::Adaptive {
        return Ok(outcome);
    }
    let (low, high) = drift::span_c(&outcome.fitted.captures);
    if let Some(model) = outcome.fitted.learned {
        feedback.say(&format!(
            "the temperature moved {:.2} degC during the session ({low:.2} to {high:.2} degC); the captures were \
             corrected by the board's learned temperature model (around {:.1} degC), which stays with the calibration",
            high - low,
            model.ref_temp_c
        ));
        return Ok(outcome);
    }
    match outcome.fitted.drift {
        Some(d) => feedback.say(&format!(
            "the temperature moved {:.2} degC during the session ({low:.2} to {high:.2} degC); the offset drift it \
             caused ({:+.2}, {:+.2}, {:+.2} mg/degC) was fitted with the calibration and goes with it to the board",
            high - low,
            d.slope_g_per_c[0] * 1e3,
            d.slope_g_per_c[1] * 1e3,
            d.slope_g_per_c[2] * 1e3
        )),
        None if high - low >= DRIFT_MIN_CHANGE_C => feedback.say(&format!(
            "the temperature moved {:.2} degC during the session; too few positions to fit the drift it caused",
            high - low
        )),
        None => {}
    }
    Ok(outcome)
}

/// How many fresh orientations to verify at, and how long each capture runs.
pub(super) fn verification(
    args: &CalibrateArgs,
    kind: SessionKind,
    rate_hz: u16,
) -> Result<(usize, CaptureLength), Error> {
    if kind != SessionKind::Adaptive {
        return Ok((
            usize::from(args.verify.unwrap_or(FIXED_VERIFY_POSITIONS)),
            CaptureLength::Seconds(VERIFY_SECONDS),
        ));
    }
    let goal = args.length.rule(rate_hz)?.verification_goal();
    Ok((usize::from(args.verify.unwrap_or(ADAPTIVE_VERIFY_POSITIONS)), CaptureLength::Goal(goal)))
}

/// The board's active calibration when a new adaptive session keeps its learned temperature model
/// (said), else none.
pub(super) fn learned_model<P: Port>(
    args: &CalibrateArgs,
    client: &mut Client<P>,
    feedback: &mut dyn Feedback,
) -> Result<Option<Calibration>, Error> {
    if args.resume.is_some() || begun_as(args) != SessionKind::Adaptive {
        return Ok(None);
    }
    let learned = drift::learned::kept(client.calibration(CalibrationSlot::Active)?);
    if let Some(model) = learned.and_then(|c| c.temperature) {
        feedback.say(&format!(
            "the board has a learned temperature model (around {:.1} degC): the captures are corrected by it and it \
             stays with the new calibration",
            model.ref_temp_c
        ));
    }
    Ok(learned)
}
