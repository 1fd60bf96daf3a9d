//! Collecting the captures of a calibration: every wanted orientation, in whatever order the board
//! arrives at them; a capture the board moved during, or that ended elsewhere, goes back to waiting.

use shared::protocol::{CaptureStats, DeviceError};
use shared::Position;

use super::stop_rule::CaptureLength;
use super::wait::{wait_for_target, Rest};
use super::{CollectOptions, Feedback, Hand, Moves, Orientation, ProcedureError, Turning};
use crate::limits::{CAPTURE_ATTEMPTS, SETTLE_SECONDS};
use crate::link::{explain, Link, LinkError, Transport};
use crate::session::{Session, SessionError};

/// Captures every target, in whatever order the board arrives at them.
pub async fn collect<T: Transport>(
    link: &mut Link<T>,
    hand: &mut dyn Hand,
    targets: &[Orientation],
    options: &CollectOptions,
    feedback: &mut dyn Feedback,
) -> Result<Session, ProcedureError> {
    let mut session = Session::default();
    let turning = Turning { hand, moves: &mut Moves::off() };
    collect_into(link, turning, targets, options, feedback, &mut session, &mut |_| Ok(())).await?;
    Ok(session)
}

/// Captures the targets `session` lacks into it, handing it to `keep` after every capture, so that
/// an interruption loses nothing captured; the moves between captures go to `turning`'s record.
pub async fn collect_into<T: Transport>(
    link: &mut Link<T>,
    turning: Turning<'_>,
    targets: &[Orientation],
    options: &CollectOptions,
    feedback: &mut dyn Feedback,
    session: &mut Session,
    keep: &mut dyn FnMut(&Session) -> Result<(), SessionError>,
) -> Result<(), ProcedureError> {
    link.clear_positions().await?;
    let captured = |t: &Orientation| session.has_capture(&t.name);
    let (mut done, mut remaining): (Vec<Orientation>, Vec<Orientation>) = targets.iter().cloned().partition(captured);
    let mut moved_in_a_row = 0;
    while !remaining.is_empty() {
        turning.moves.present(link, turning.hand, &remaining[0], feedback).await?;
        let rest =
            Rest { limit: options.wait_limit, settle_seconds: SETTLE_SECONDS, rested_s: turning.moves.rested_s() };
        let index = wait_for_target(link, &remaining, &done, rest, feedback).await?;
        feedback.say(&format!("{} found; averaging for {} s", remaining[index].name, options.seconds));
        let length = CaptureLength::Seconds(options.seconds);
        let Some((stats, face)) = capture_at(link, &remaining[index], length, feedback).await? else {
            moved_in_a_row += 1;
            if moved_in_a_row >= CAPTURE_ATTEMPTS {
                return Err(ProcedureError::KeptMoving { attempts: CAPTURE_ATTEMPTS });
            }
            continue;
        };
        moved_in_a_row = 0;
        let target = remaining.remove(index);
        session.captures.push(crate::session::CaptureRecord::at(
            &target.name,
            Some(target.clone()),
            face,
            stats,
            link.unix_time_s(),
        ));
        turning.moves.captured(session);
        keep(session)?;
        done.push(target);
        feedback.say(&format!("captured {} of {}", done.len(), targets.len()));
    }
    Ok(())
}

/// One capture at `target`; `None` when the board moved during it or its mean lies outside the
/// target's tolerance (the person turned it elsewhere and held it there): the wait starts again, so
/// a capture is never kept under the name of an orientation it was not taken at.
pub(super) async fn capture_at<T: Transport>(
    link: &mut Link<T>,
    target: &Orientation,
    length: CaptureLength,
    feedback: &mut dyn Feedback,
) -> Result<Option<(CaptureStats, Option<Position>)>, ProcedureError> {
    let result = length.capture(link, feedback).await;
    feedback.progress_done();
    let (stats, face) = match result {
        Err(LinkError::Device(error @ DeviceError::Moved { .. })) => {
            feedback.say(&format!("{}; trying again", explain(&error)));
            return Ok(None);
        }
        other => other?,
    };
    let tilt = target.tilt_deg(stats.mean_g.map(f64::from));
    if tilt > target.tolerance_deg {
        feedback.say(&format!("the board ended {tilt:.1} degrees from {}: hold it there and keep still", target.name));
        return Ok(None);
    }
    Ok(Some((stats, face)))
}
