//! Collecting the captures of a calibration: every wanted orientation, in whatever order the board
//! arrives at them, each capture retried while the board moves.

use shared::protocol::{CaptureStats, DeviceError};
use shared::Position;

use super::wait::wait_for_target;
use super::{CollectOptions, Feedback, Hand, Orientation, ProcedureError};
use crate::link::{explain, Client, LinkError, Port};
use crate::session::{CaptureRecord, Session, SessionError};

/// Captures of a position tried before giving up on a board that keeps moving.
const CAPTURE_ATTEMPTS: usize = 5;

/// Captures every target, in whatever order the board arrives at them.
pub fn collect<P: Port>(
    client: &mut Client<P>,
    hand: &mut dyn Hand,
    targets: &[Orientation],
    options: &CollectOptions,
    feedback: &mut dyn Feedback,
) -> Result<Session, ProcedureError> {
    let mut session = Session::default();
    collect_into(client, hand, targets, options, feedback, &mut session, &mut |_| Ok(()))?;
    Ok(session)
}

/// Captures the targets `session` lacks into it, handing it to `keep` after every capture, so that
/// an interruption loses nothing captured.
pub fn collect_into<P: Port>(
    client: &mut Client<P>,
    hand: &mut dyn Hand,
    targets: &[Orientation],
    options: &CollectOptions,
    feedback: &mut dyn Feedback,
    session: &mut Session,
    keep: &mut dyn FnMut(&Session) -> Result<(), SessionError>,
) -> Result<(), ProcedureError> {
    client.clear_positions()?;
    let captured = |t: &Orientation| session.captures.iter().any(|c| c.name == t.name);
    let (mut done, mut remaining): (Vec<Orientation>, Vec<Orientation>) = targets.iter().cloned().partition(captured);
    while !remaining.is_empty() {
        hand.present(&remaining[0], feedback)?;
        let index = wait_for_target(client, &remaining, &done, options.wait_limit, feedback)?;
        let target = remaining.remove(index);
        feedback.say(&format!("{} found; averaging for {} s", target.name, options.seconds));
        let (stats, face) = capture(client, options.seconds, feedback)?;
        session.captures.push(CaptureRecord::now(&target.name, Some(target.clone()), face, stats));
        keep(session)?;
        done.push(target);
        feedback.say(&format!("captured {} of {}", done.len(), targets.len()));
    }
    Ok(())
}

/// One capture with its progress shown, retried while the board moves.
pub(super) fn capture<P: Port>(
    client: &mut Client<P>,
    seconds: u8,
    feedback: &mut dyn Feedback,
) -> Result<(CaptureStats, Option<Position>), ProcedureError> {
    for attempt in 1..=CAPTURE_ATTEMPTS {
        let result = client.capture(seconds, |p| feedback.progress(p.samples, p.total_samples));
        feedback.progress_done();
        match result {
            Err(LinkError::Device(error @ DeviceError::Moved { .. })) if attempt < CAPTURE_ATTEMPTS => {
                feedback.say(&format!("{}; trying again", explain(&error)));
            }
            other => return Ok(other?),
        }
    }
    Err(ProcedureError::KeptMoving { attempts: CAPTURE_ATTEMPTS })
}
