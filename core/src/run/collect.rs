//! Collecting the captures of a calibration, one loop for every order: the positions a [`Plan`]
//! asks for next (every wanted one in whatever order the board arrives at them, or the adaptive
//! drift-cancelling order), each presented, waited for and captured; a capture the board moved
//! during, or that ended elsewhere, goes back to presenting it.

use std::time::Duration;

use shared::protocol::{CaptureStats, DeviceError};
use shared::Position;

use super::adaptive::{AdaptiveOptions, AdaptiveOrder, BoardClock};
use super::stop_rule::CaptureLength;
use super::wait::{wait_for_target, Rest};
use super::wanted::Wanted;
use super::{Feedback, Hand, Moves, Orientation, ProcedureError, Turning};
use crate::limits::CAPTURE_ATTEMPTS;
use crate::link::{explain, Link, LinkError, Transport};
use crate::session::{CaptureRecord, Session, SessionError, SessionKind};

/// How the captures of a collection in arrival order run.
#[derive(Debug, Clone)]
pub struct CollectOptions {
    /// Capture length, in seconds.
    pub seconds: u8,
    /// Give up waiting for a position after this long (`None`: wait for the person).
    pub wait_limit: Option<Duration>,
}

/// What a collection measured besides its captures.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Collected {
    /// The board's clock when the first capture started, in seconds (when the plan has the clock).
    pub first_capture_s: Option<f64>,
}

/// The positions a collection asks for, how long each is averaged and how long it waits.
pub struct Plan {
    order: Order,
    targets: Vec<Orientation>,
    length: CaptureLength,
    wait_limit: Option<Duration>,
    clock: Option<BoardClock>,
}

/// The order positions are asked for in.
enum Order {
    /// Every target, in whatever order the board arrives at them.
    AsArrived,
    /// One at a time in drift-cancelling order until the fit predicts the target, then the first again.
    Adaptive(AdaptiveOrder),
}

impl Plan {
    /// Every one of `targets` with captures of `options.seconds`, in whatever order the board arrives.
    pub fn as_arrived(targets: &[Orientation], options: &CollectOptions) -> Self {
        let length = CaptureLength::Seconds(options.seconds);
        Plan { order: Order::AsArrived, targets: targets.to_vec(), length, wait_limit: options.wait_limit, clock: None }
    }

    /// `targets` in drift-cancelling order, each averaged until `options.rule` stops it.
    pub fn adaptive(targets: &[Orientation], options: &AdaptiveOptions) -> Self {
        Plan {
            order: Order::Adaptive(AdaptiveOrder::new(targets, options.rule.clone())),
            targets: targets.to_vec(),
            length: CaptureLength::Goal(options.rule.goal()),
            wait_limit: options.wait_limit,
            clock: options.clock.clone(),
        }
    }

    /// What to capture next, given the session so far; `None` once the collection is complete.
    fn next(&mut self, session: &Session, hand: &mut dyn Hand, feedback: &mut dyn Feedback) -> Option<Wanted> {
        match &mut self.order {
            Order::AsArrived => {
                let captured = |t: &&Orientation| session.has_capture(&t.name);
                let (done, positions): (Vec<&Orientation>, Vec<&Orientation>) = self.targets.iter().partition(captured);
                let cloned = |list: Vec<&Orientation>| list.into_iter().cloned().collect();
                (!positions.is_empty()).then(|| Wanted {
                    positions: cloned(positions),
                    done: cloned(done),
                    closing: false,
                })
            }
            Order::Adaptive(order) => order.next(session, hand, feedback),
        }
    }

    /// What the person is told once a capture is kept.
    fn captured_line(&self, session: &Session, target: &Orientation, stats: &CaptureStats) -> String {
        match &self.order {
            Order::AsArrived => {
                let taken = self.targets.iter().filter(|t| session.has_capture(&t.name)).count();
                format!("captured {taken} of {}", self.targets.len())
            }
            Order::Adaptive(order) => format!("{}: {}", target.name, order.rule().why_stopped(stats)),
        }
    }
}

/// Captures every target, in whatever order the board arrives at them, into a new session.
pub async fn collect<T: Transport>(
    link: &mut Link<T>,
    hand: &mut dyn Hand,
    targets: &[Orientation],
    options: &CollectOptions,
    feedback: &mut dyn Feedback,
) -> Result<Session, ProcedureError> {
    let mut session = Session::default();
    let turning = Turning { hand, moves: &mut Moves::off() };
    let mut plan = Plan::as_arrived(targets, options);
    gather(link, turning, &mut plan, feedback, &mut session, &mut |_| Ok(())).await?;
    Ok(session)
}

/// Captures the targets `session` lacks into it, in whatever order the board arrives at them,
/// keeping it after every capture ([`gather`] by [`Plan::as_arrived`]).
pub async fn collect_into<T: Transport>(
    link: &mut Link<T>,
    turning: Turning<'_>,
    targets: &[Orientation],
    options: &CollectOptions,
    feedback: &mut dyn Feedback,
    session: &mut Session,
    keep: &mut dyn FnMut(&Session) -> Result<(), SessionError>,
) -> Result<(), ProcedureError> {
    let mut plan = Plan::as_arrived(targets, options);
    gather(link, turning, &mut plan, feedback, session, keep).await.map(|_| ())
}

/// Captures positions of `targets` in drift-cancelling order until the fit predicts the rule's
/// target (or every target is taken), then the first position again ([`gather`] by [`Plan::adaptive`]).
pub async fn collect_adaptive<T: Transport>(
    link: &mut Link<T>,
    turning: Turning<'_>,
    targets: &[Orientation],
    options: &AdaptiveOptions,
    feedback: &mut dyn Feedback,
    session: &mut Session,
    keep: &mut dyn FnMut(&Session) -> Result<(), SessionError>,
) -> Result<Collected, ProcedureError> {
    gather(link, turning, &mut Plan::adaptive(targets, options), feedback, session, keep).await
}

/// Captures what `plan` asks for that `session` lacks into it, handing it to `keep` after every
/// capture, so that an interruption loses nothing captured; the moves between captures go to
/// `turning`'s record.
pub async fn gather<T: Transport>(
    link: &mut Link<T>,
    mut turning: Turning<'_>,
    plan: &mut Plan,
    feedback: &mut dyn Feedback,
    session: &mut Session,
    keep: &mut dyn FnMut(&Session) -> Result<(), SessionError>,
) -> Result<Collected, ProcedureError> {
    let mut collected = Collected::default();
    link.clear_positions().await?;
    if let Order::Adaptive(_) = plan.order {
        session.kind = SessionKind::Adaptive;
    }
    while let Some(wanted) = plan.next(session, turning.hand, feedback) {
        let (target, stats) = take(link, &mut turning, &wanted, plan, feedback, session, &mut collected).await?;
        if wanted.closing {
            session.captures.last_mut().into_iter().for_each(|c| c.closing = true);
        }
        keep(session)?;
        feedback.say(&plan.captured_line(session, &target, &stats));
    }
    Ok(collected)
}

/// One of `wanted`'s positions: presented, waited for, captured (again while the board moves, at
/// most [`CAPTURE_ATTEMPTS`] times in a row), recorded; the position taken and its statistics.
async fn take<T: Transport>(
    link: &mut Link<T>,
    turning: &mut Turning<'_>,
    wanted: &Wanted,
    plan: &Plan,
    feedback: &mut dyn Feedback,
    session: &mut Session,
    collected: &mut Collected,
) -> Result<(Orientation, CaptureStats), ProcedureError> {
    let (asked, length) = (&wanted.positions[0], plan.length);
    for _ in 0..CAPTURE_ATTEMPTS {
        turning.moves.present(link, turning.hand, asked, feedback).await?;
        let target = &wanted.positions[arrived(link, turning, wanted, plan, feedback).await?];
        if let CaptureLength::Seconds(seconds) = length {
            feedback.say(&format!("{} found; averaging for {seconds} s", target.name));
        }
        let started = plan.clock.as_ref().map(|clock| clock());
        collected.first_capture_s = collected.first_capture_s.or(started);
        if let Some((stats, face)) = capture_at(link, target, length, feedback).await? {
            session.captures.push(CaptureRecord::at(
                &target.name,
                Some(target.clone()),
                face,
                stats,
                link.unix_time_s(),
            ));
            turning.moves.captured(session);
            return Ok((target.clone(), stats));
        }
    }
    Err(ProcedureError::KeptMoving { attempts: CAPTURE_ATTEMPTS })
}

/// Which of `wanted`'s positions the board came to rest at: the one asked for at once when the move
/// just recorded ended there, still, long enough; else as the live windows see it.
async fn arrived<T: Transport>(
    link: &mut Link<T>,
    turning: &Turning<'_>,
    wanted: &Wanted,
    plan: &Plan,
    feedback: &mut dyn Feedback,
) -> Result<usize, ProcedureError> {
    let settle_seconds = plan.length.settle_seconds();
    if turning.moves.rests_at(&wanted.positions[0], settle_seconds) {
        return Ok(0);
    }
    let rest = Rest { limit: plan.wait_limit, settle_seconds, rested_s: turning.moves.rested_s() };
    wait_for_target(link, &wanted.positions, &wanted.done, rest, feedback).await
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
