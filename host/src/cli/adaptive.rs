//! What `calibrate`'s arguments make of a session's kind (quick, fixed-length captures, or the
//! adaptive default) when it is begun and when it is resumed, and the board's learned temperature
//! model a new adaptive session keeps. The run itself is the core's (`run::board`).

use shared::protocol::CalibrationSlot;
use shared::Calibration;

use super::args::CalibrateArgs;
use crate::error::Error;
use crate::fit::drift;
use crate::link::{Client, Port};
use crate::procedure::Feedback;
use crate::session::{Session, SessionKind};

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
