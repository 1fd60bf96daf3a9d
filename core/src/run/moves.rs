//! Recording the moves between still positions: from the end of one capture, the raw gyro at the
//! sensor's full rate until the board has turned and come to rest again, every sample numbered; a
//! move with a lost or clipped sample, or one the board left again before the next capture, is
//! named and dropped (a lost sample corrupts the turn's integral), never the session.

use shared::orientation::angle_between_deg;
use shared::protocol::{Sample, StreamKind, GYRO_RANGE};

use super::{Feedback, Hand, Orientation, ProcedureError};
use crate::limits::{
    GYRO_CLIPPED_FRACTION, MAX_MOVE_SECONDS, MOVED_AFTER_TURN_DEG, MOVE_STARTED_DPS, MOVE_STILL_DPS,
    MOVE_STILL_SECONDS, MOVE_TILTED_DEG,
};
use crate::link::{Link, StreamRequest, Transport};
use crate::session::Session;

/// Who turns the board between captures, and the moves recorded meanwhile (the gyro's G is fitted
/// to them).
pub struct Turning<'a> {
    /// The person, or the tool's own hand on the simulated board.
    pub hand: &'a mut dyn Hand,
    /// The moves between captures, recorded as the board is turned.
    pub moves: &'a mut Moves,
}

/// One move between two captures of a session, recorded whole.
#[derive(Debug, Clone, PartialEq)]
pub struct RecordedMove {
    /// Index in the session's captures of the pose before.
    pub from: usize,
    /// Index of the pose after.
    pub to: usize,
    /// Raw gyro samples, deg/s, one every `interval_s`, none missing.
    pub rates_dps: Vec<[f64; 3]>,
    /// Time between samples, in seconds.
    pub interval_s: f64,
}

/// The moves of one calibration run: those recorded whole, and why others were dropped.
#[derive(Debug, Default)]
pub struct Moves {
    rate_hz: u16,
    /// The last capture (index, its gyro bias, its mean accel): where the next move starts.
    start: Option<(usize, Pose)>,
    /// A move recorded, waiting for the capture that ends it, with its mean raw accel at the end.
    pending: Option<(usize, Recording)>,
    /// The moves recorded whole, in order.
    pub recorded: Vec<RecordedMove>,
    /// Each dropped move, named with its cause.
    pub dropped: Vec<String>,
}

/// The samples of a move that came to rest.
#[derive(Debug, Clone)]
pub(super) struct Recording {
    pub(super) samples: Vec<Sample>,
    pub(super) end_mean_g: [f64; 3],
    target: String,
}

impl Recording {
    fn rates_dps(&self) -> Vec<[f64; 3]> {
        self.samples.iter().map(|s| s.gyro_dps.map(f64::from)).collect()
    }
}

impl Moves {
    /// Records moves from the sensor's stream at `rate_hz` (its sample rate: every sample).
    pub fn at(rate_hz: u16) -> Self {
        Moves { rate_hz, ..Moves::default() }
    }

    /// Records nothing (a rate of 0).
    pub fn off() -> Self {
        Moves::default()
    }

    /// Asks `hand` for `target` and, when the board rests at a captured pose, records the move.
    pub async fn present<T: Transport>(
        &mut self,
        link: &mut Link<T>,
        hand: &mut dyn Hand,
        target: &Orientation,
        feedback: &mut dyn Feedback,
    ) -> Result<(), ProcedureError> {
        if let Some((_, stale)) = self.pending.take() {
            self.dropped.push(format!("move to {}: the capture after it was taken again", stale.target));
        }
        let start = self.start.take();
        hand.present(target, feedback)?;
        let Some((from, pose)) = start.filter(|_| self.rate_hz > 0) else { return Ok(()) };
        feedback.live(&format!("recording the gyro while you turn the board to {}, until it rests", target.name));
        match record(link, self.rate_hz, pose, &target.name).await? {
            Ok(recording) => self.pending = Some((from, recording)),
            Err(problem) => self.dropped.push(format!("move to {}: {problem}; dropped", target.name)),
        }
        Ok(())
    }

    /// How long, in seconds, the board was just seen at rest: the still end of the move recorded
    /// since the last capture (the wait for the position counts it), else 0.
    pub fn rested_s(&self) -> f64 {
        if self.pending.is_some() {
            MOVE_STILL_SECONDS
        } else {
            0.0
        }
    }

    /// Whether the move just recorded ended at rest within `target`'s tolerance for at least
    /// `settle_s`: then the board was seen where it should be, still, and the wait for it is done.
    pub fn rests_at(&self, target: &Orientation, settle_s: f64) -> bool {
        let at_target = |r: &Recording| target.tilt_deg(r.end_mean_g) <= target.tolerance_deg;
        MOVE_STILL_SECONDS >= settle_s && self.pending.as_ref().is_some_and(|(_, r)| at_target(r))
    }

    /// The last capture of `session` was just taken: it ends the pending move and starts the next.
    pub fn captured(&mut self, session: &Session) {
        let Some(to) = session.captures.len().checked_sub(1) else { return };
        let stats = &session.captures[to].stats;
        if let Some((from, recording)) = self.pending.take() {
            let moved_deg = angle_between_deg(recording.end_mean_g, stats.mean_g.map(f64::from));
            if moved_deg > MOVED_AFTER_TURN_DEG {
                self.dropped.push(format!(
                    "move to {}: the board moved {moved_deg:.2} degrees after the turn ended; dropped",
                    recording.target
                ));
            } else {
                let interval_s = 1.0 / f64::from(self.rate_hz);
                self.recorded.push(RecordedMove { from, to, rates_dps: recording.rates_dps(), interval_s });
            }
        }
        self.start =
            Some((to, Pose { bias_dps: stats.gyro_mean_dps.map(f64::from), mean_g: stats.mean_g.map(f64::from) }));
    }
}

/// A still pose a move starts from, as its capture measured it.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Pose {
    bias_dps: [f64; 3],
    mean_g: [f64; 3],
}

/// Why a move was not recorded whole.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Problem {
    Lost(u32),
    Clipped(usize),
    AlreadyMoving,
    NeverStill,
    NoTurnSeen,
}

impl std::fmt::Display for Problem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Problem::Lost(n) => write!(f, "{n} gyro samples lost on the way (a gap corrupts the turn)"),
            Problem::Clipped(n) => {
                write!(
                    f,
                    "{n} gyro samples at the end of the +-{} deg/s range: turn more slowly",
                    GYRO_RANGE.full_scale_dps()
                )
            }
            Problem::AlreadyMoving => write!(f, "the board was already turning when the recording began"),
            Problem::NeverStill => write!(f, "the board did not turn and come to rest within {MAX_MOVE_SECONDS} s"),
            Problem::NoTurnSeen => write!(f, "the board came to rest elsewhere without the gyro seeing it turn"),
        }
    }
}

/// Streams raw samples from now until the board has turned and rested [`MOVE_STILL_SECONDS`].
async fn record<T: Transport>(
    link: &mut Link<T>,
    rate_hz: u16,
    pose: Pose,
    target: &str,
) -> Result<Result<Recording, Problem>, ProcedureError> {
    let request = StreamRequest { kind: StreamKind::Raw, rate_hz, count: MAX_MOVE_SECONDS * u32::from(rate_hz) };
    let mut watch = Watch::new(pose.bias_dps, (MOVE_STILL_SECONDS * f64::from(rate_hz)).ceil() as usize);
    watch.rest_g = Some(pose.mean_g);
    let tally = link.stream_while(request, |sample| watch.push(sample)).await?;
    Ok(watch.finish(tally.lost(), target))
}

/// Watches a move's samples: when it began, and whether it has come to rest.
#[derive(Debug)]
pub(super) struct Watch {
    bias: [f64; 3],
    still_needed: usize,
    samples: Vec<Sample>,
    started: bool,
    turn_seen: bool,
    already_moving: bool,
    still_run: usize,
    /// The move has ended: samples still queued after the stream's cancel are ignored.
    done: bool,
    /// The accelerometer at the rest the move starts from (else its first sample).
    pub(super) rest_g: Option<[f64; 3]>,
}

impl Watch {
    pub(super) fn new(bias: [f64; 3], still_needed: usize) -> Self {
        Watch {
            bias,
            still_needed,
            samples: Vec::new(),
            started: false,
            turn_seen: false,
            already_moving: false,
            still_run: 0,
            done: false,
            rest_g: None,
        }
    }

    /// Takes one sample; `false` once the move has ended (or cannot be used).
    pub(super) fn push(&mut self, sample: &Sample) -> bool {
        if self.done {
            return false;
        }
        let rate = self.rate_off_bias(sample);
        self.already_moving = self.samples.is_empty() && rate > MOVE_STARTED_DPS;
        self.samples.push(*sample);
        self.turn_seen |= rate > MOVE_STARTED_DPS;
        self.started |= self.turn_seen || self.tilted_deg(sample) > MOVE_TILTED_DEG;
        self.still_run = if self.started && rate < MOVE_STILL_DPS { self.still_run + 1 } else { 0 };
        self.done = self.already_moving || self.still_run >= self.still_needed;
        !self.done
    }

    /// How far, in degrees, the accelerometer's direction has moved from the rest the move starts
    /// at: a board put down elsewhere without the gyro seeing a turn (the simulator's `place`,
    /// perhaps before the first sample) ends the move too.
    fn tilted_deg(&self, sample: &Sample) -> f64 {
        let first = self.samples.first().map_or(sample.accel_g, |s| s.accel_g).map(f64::from);
        angle_between_deg(self.rest_g.unwrap_or(first), sample.accel_g.map(f64::from))
    }

    fn rate_off_bias(&self, sample: &Sample) -> f64 {
        let off = [0, 1, 2].map(|k| f64::from(sample.gyro_dps[k]) - self.bias[k]);
        shared::linalg::norm(off)
    }

    /// The recording, or why it cannot be used.
    pub(super) fn finish(self, lost: u32, target: &str) -> Result<Recording, Problem> {
        let limit = f64::from(GYRO_RANGE.full_scale_dps()) * GYRO_CLIPPED_FRACTION;
        let clipped = self.samples.iter().filter(|s| s.gyro_dps.iter().any(|w| f64::from(w.abs()) >= limit)).count();
        match () {
            _ if self.already_moving => Err(Problem::AlreadyMoving),
            _ if lost > 0 => Err(Problem::Lost(lost)),
            _ if clipped > 0 => Err(Problem::Clipped(clipped)),
            _ if self.still_run < self.still_needed => Err(Problem::NeverStill),
            _ if !self.turn_seen => Err(Problem::NoTurnSeen),
            _ => Ok(self.recording(target)),
        }
    }

    fn recording(self, target: &str) -> Recording {
        let tail = &self.samples[self.samples.len() - self.still_needed..];
        let n = tail.len() as f64;
        let end_mean_g = [0, 1, 2].map(|k| tail.iter().map(|s| f64::from(s.accel_g[k])).sum::<f64>() / n);
        Recording { samples: self.samples, end_mean_g, target: target.to_owned() }
    }
}

#[cfg(test)]
mod tests;
