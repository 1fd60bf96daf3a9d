//! Waiting for the board: one mechanism (a deadline, live windows of raw samples, two accepted
//! windows in a row) serves both the wait for a wanted orientation and the wait for a fresh one.

use std::time::Duration;

use shared::orientation::angle_between_deg;
use shared::protocol::StreamKind;

use super::{Feedback, Orientation, ProcedureError};
use crate::limits::{FRESH_DEG, MAX_GRAVITY_ERROR_G, STILL_ACCEL_STD_G, ZERO_READING_G};
use crate::link::{Link, StreamRequest, Transport};

/// The live window: half a second of raw samples.
pub(super) const LIVE_WINDOW: StreamRequest = StreamRequest { kind: StreamKind::Raw, rate_hz: 20, count: 10 };

/// What one live window showed: the mean direction and whether the board was still.
#[derive(Debug, Clone, Copy)]
struct Window {
    mean: [f64; 3],
    still: bool,
}

/// How long to wait for the board, and how long it must rest where it is wanted.
#[derive(Debug, Clone, Copy)]
pub(super) struct Rest {
    /// Give up after this long (`None`: wait for the person).
    pub limit: Option<Duration>,
    /// How long the board must be still, in seconds (rounded up to whole windows).
    pub settle_seconds: f64,
    /// How long it was seen still just before (the end of a recorded move), in seconds: counted
    /// towards `settle_seconds` when the first window finds it where it should be.
    pub rested_s: f64,
}

/// Waits until the board rests within tolerance of one of the `remaining` targets; says how far it
/// is and refuses a position already captured (`done`). Returns the index in `remaining`.
pub(super) async fn wait_for_target<T: Transport>(
    link: &mut Link<T>,
    remaining: &[Orientation],
    done: &[Orientation],
    rest: Rest,
    feedback: &mut dyn Feedback,
) -> Result<usize, ProcedureError> {
    let gave_up = || {
        let wanted: Vec<&str> = remaining.iter().map(|t| t.name.as_str()).collect();
        ProcedureError::NeverAtTarget { wanted: wanted.join(", ") }
    };
    wait_for_rest(link, rest, feedback, gave_up, |window| judge_target(window, remaining, done)).await
}

/// What a window says about the remaining targets: a line for the user, and the index of the
/// target reached when the board is still within its tolerance. The line measures to the target
/// the instruction asked for (`remaining[0]`), unless the board is already at another wanted one,
/// which it then names as taken instead.
fn judge_target(window: Window, remaining: &[Orientation], done: &[Orientation]) -> (String, Option<usize>) {
    let tilt = |t: &Orientation| t.tilt_deg(window.mean);
    let Some((index, nearest)) = remaining.iter().enumerate().min_by(|a, b| tilt(a.1).total_cmp(&tilt(b.1))) else {
        return ("no position left to capture".into(), None);
    };
    let asked = &remaining[0];
    if let Some(repeat) = done.iter().find(|t| tilt(t) < t.tolerance_deg.min(tilt(nearest))) {
        return (format!("{} is already captured: turn the board to {}", repeat.name, asked.name), None);
    }
    let motion = if window.still { "still" } else { "moving" };
    let (target, index) = match tilt(nearest) <= nearest.tolerance_deg {
        true => (nearest, index),
        false => (asked, 0),
    };
    let line = match target.name == asked.name {
        true => format!("{:.1} degrees from {} ({motion})", tilt(asked), asked.name),
        false => format!(
            "at {} ({:.1} degrees, {motion}), also wanted: taking it before {}",
            target.name,
            tilt(target),
            asked.name
        ),
    };
    (line, (window.still && tilt(target) <= target.tolerance_deg).then_some(index))
}

/// Waits until the board rests for `rest`'s settling time at an orientation at least [`FRESH_DEG`] from
/// every one in `used`; returns it.
pub(super) async fn wait_for_fresh<T: Transport>(
    link: &mut Link<T>,
    used: &[[f64; 3]],
    rest: Rest,
    feedback: &mut dyn Feedback,
) -> Result<[f64; 3], ProcedureError> {
    wait_for_rest(
        link,
        rest,
        feedback,
        || ProcedureError::NeverFresh,
        |window| {
            let fresh = used.iter().all(|u| angle_between_deg(window.mean, *u) >= FRESH_DEG);
            let line = match (window.still, fresh) {
                (_, false) => "this orientation was used already (to calibrate or verify): turn the board to a new one",
                (false, true) => "moving: hold the board still",
                (true, true) => "still",
            };
            (line.to_owned(), (window.still && fresh).then_some(window.mean))
        },
    )
    .await
}

/// Streams live windows, showing what `judge` says of each, until two windows in a row are accepted
/// (`judge` returns a value only for a window that is still and where it should be) over `rest`'s
/// settling time; gives up after its limit with the error `gave_up` makes.
async fn wait_for_rest<T: Transport, R>(
    link: &mut Link<T>,
    rest: Rest,
    feedback: &mut dyn Feedback,
    gave_up: impl Fn() -> ProcedureError,
    mut judge: impl FnMut(Window) -> (String, Option<R>),
) -> Result<R, ProcedureError> {
    let (started, mut streak) = (link.now(), Streak::over(rest.settle_seconds).after_rest(rest.rested_s));
    loop {
        if rest.limit.is_some_and(|l| link.now().saturating_sub(started) > l) {
            return Err(gave_up());
        }
        let window = live_window(link).await?;
        let (line, verdict) = match not_gravity(&window) {
            Some(line) => (line, None),
            None => judge(window),
        };
        feedback.live(&line);
        if let Some(value) = streak.settled(verdict) {
            return Ok(value);
        }
    }
}

/// What the sensor reads when its magnitude cannot be gravity at rest (then it is no position at
/// all), and what that usually means.
fn not_gravity(window: &Window) -> Option<String> {
    let magnitude_g = shared::linalg::norm(window.mean);
    if (magnitude_g - 1.0).abs() <= MAX_GRAVITY_ERROR_G {
        return None;
    }
    let meaning = if magnitude_g < ZERO_READING_G {
        "it returns zeros: it is asleep, or not an MPU-6050; check `accelcal info` and the wiring"
    } else if window.still {
        "not the 1 g of gravity: the range setting or the sensor is wrong; check `accelcal info`"
    } else {
        "not the 1 g of gravity at rest: hold the board still"
    };
    Some(format!("the sensor reads {magnitude_g:.2} g, {meaning}"))
}

/// Accepted live windows in a row that make [`crate::limits::SETTLE_SECONDS`].
#[cfg(test)]
fn settle_windows() -> usize {
    windows_for(crate::limits::SETTLE_SECONDS)
}

/// Live windows that cover `seconds` (at least one).
fn windows_for(seconds: f64) -> usize {
    ((seconds * f64::from(LIVE_WINDOW.rate_hz) / f64::from(LIVE_WINDOW.count)).ceil() as usize).max(1)
}

/// Windows accepted in a row: a board counts as at rest only after `needed` accepted windows in a
/// row, so that one lucky half second while it is being turned does not count.
#[derive(Debug)]
pub(super) struct Streak {
    accepted_in_a_row: usize,
    needed: usize,
}

impl Streak {
    /// A streak of the windows that cover `seconds`.
    fn over(seconds: f64) -> Self {
        Streak { accepted_in_a_row: 0, needed: windows_for(seconds) }
    }

    /// The same streak with `rested_s` seconds of rest already seen counted as accepted windows
    /// (whole windows only); the first window rejected resets it like any other.
    fn after_rest(self, rested_s: f64) -> Self {
        let window_s = f64::from(LIVE_WINDOW.count) / f64::from(LIVE_WINDOW.rate_hz);
        Streak { accepted_in_a_row: (rested_s / window_s + 1e-9).floor() as usize, ..self }
    }

    /// Counts one window's verdict; the value once it completes the run of accepted windows.
    fn settled<R>(&mut self, verdict: Option<R>) -> Option<R> {
        match verdict {
            Some(value) if self.accepted_in_a_row + 1 >= self.needed => return Some(value),
            Some(_) => self.accepted_in_a_row += 1,
            None => self.accepted_in_a_row = 0,
        }
        None
    }
}

/// One live window of raw samples: their mean direction and whether the board was still.
async fn live_window<T: Transport>(link: &mut Link<T>) -> Result<Window, ProcedureError> {
    let mut samples = Vec::with_capacity(LIVE_WINDOW.count as usize);
    link.stream(LIVE_WINDOW, |sample| samples.push(sample.accel_g.map(f64::from))).await?;
    Ok(window_of(&samples))
}

/// The mean of `samples` and whether their scatter on every axis is below the stillness threshold.
fn window_of(samples: &[[f64; 3]]) -> Window {
    let n = samples.len().max(1) as f64;
    let mean = [0, 1, 2].map(|k| samples.iter().map(|s| s[k]).sum::<f64>() / n);
    let spread = [0, 1, 2]
        .map(|k| (samples.iter().map(|s| (s[k] - mean[k]).powi(2)).sum::<f64>() / n).sqrt())
        .into_iter()
        .fold(0.0, f64::max);
    Window { mean, still: spread < STILL_ACCEL_STD_G && !samples.is_empty() }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::limits::SETTLE_SECONDS;
    use shared::Position;

    #[test]
    fn a_window_is_still_only_below_the_threshold_on_every_axis() {
        let wobble = |amplitude: f64| [[0.0, amplitude, 1.0], [0.0, -amplitude, 1.0]];
        assert!(window_of(&wobble(0.99 * STILL_ACCEL_STD_G)).still);
        assert!(!window_of(&wobble(1.01 * STILL_ACCEL_STD_G)).still);
        assert!(!window_of(&[]).still);
        assert_eq!(window_of(&wobble(0.005)).mean, [0.0, 0.0, 1.0]);
    }

    #[test]
    fn the_board_is_at_rest_only_after_two_seconds_of_accepted_windows_in_a_row() {
        assert_eq!(settle_windows(), 4, "2 s of half-second windows");
        let mut streak = Streak::over(SETTLE_SECONDS);
        assert_eq!(streak.settled(Some(1)), None);
        assert_eq!(streak.settled(None::<i32>), None);
        assert_eq!([2, 3, 4].map(|v| streak.settled(Some(v))), [None; 3]);
        assert_eq!(streak.settled(Some(5)), Some(5));
        // Half a second of rest seen before (a recorded move's end) counts as one window.
        let mut rested = Streak::over(SETTLE_SECONDS).after_rest(0.5);
        assert_eq!([1, 2].map(|v| rested.settled(Some(v))), [None; 2]);
        assert_eq!(rested.settled(Some(3)), Some(3));
        let mut rested = Streak::over(SETTLE_SECONDS).after_rest(0.5);
        assert_eq!(rested.settled(None::<i32>), None);
        assert_eq!([1, 2, 3].map(|v| rested.settled(Some(v))), [None; 3], "a rejected window resets the credit");
    }

    #[test]
    fn the_live_line_measures_to_the_instructed_target_unless_the_board_is_at_another_wanted_one() {
        let (plus_z, minus_z) = (Orientation::face(Position::PosZ), Orientation::face(Position::NegZ));
        let tilted = |deg: f64| [deg.to_radians().sin(), 0.0, deg.to_radians().cos()];
        let remaining = [minus_z.clone(), plus_z.clone()];
        let (line, verdict) = judge_target(Window { mean: tilted(40.0), still: true }, &remaining, &[]);
        assert_eq!((line.as_str(), verdict), ("140.0 degrees from -Z (still)", None));
        let (line, verdict) = judge_target(Window { mean: tilted(1.0), still: true }, &remaining, &[]);
        assert_eq!((line.as_str(), verdict), ("at +Z (1.0 degrees, still), also wanted: taking it before -Z", Some(1)));
    }

    #[test]
    fn a_reading_far_from_1_g_is_no_position_and_says_what_the_sensor_reads() {
        let zeros = Window { mean: [0.0, 0.0, 0.001], still: true };
        let line = not_gravity(&zeros).unwrap();
        assert_eq!(line, "the sensor reads 0.00 g, it returns zeros: it is asleep, or not an MPU-6050; check `accelcal info` and the wiring");
        let half = Window { mean: [0.0, 0.0, 0.5], still: true };
        assert!(not_gravity(&half).unwrap().starts_with("the sensor reads 0.50 g, not the 1 g"));
        let limit = 1.0 - MAX_GRAVITY_ERROR_G;
        assert_eq!(not_gravity(&Window { mean: [0.0, 0.0, limit + 1e-6], still: true }), None);
        assert!(not_gravity(&Window { mean: [0.0, 0.0, limit - 1e-3], still: true }).is_some());
    }

    #[test]
    fn a_target_is_accepted_still_and_within_its_tolerance_and_a_repeat_is_named() {
        let (plus_z, minus_z) = (Orientation::face(Position::PosZ), Orientation::face(Position::NegZ));
        let tilted = |deg: f64| [deg.to_radians().sin(), 0.0, deg.to_radians().cos()];
        let still = |deg| Window { mean: tilted(deg), still: true };
        let remaining = [minus_z.clone(), plus_z.clone()];
        assert_eq!(judge_target(still(0.9 * plus_z.tolerance_deg), &remaining, &[]).1, Some(1));
        assert_eq!(judge_target(still(1.1 * plus_z.tolerance_deg), &remaining, &[]).1, None);
        assert_eq!(judge_target(Window { still: false, ..still(0.0) }, &remaining, &[]).1, None);
        let (line, verdict) = judge_target(still(0.0), &[minus_z], &[plus_z]);
        assert_eq!((line.as_str(), verdict), ("+Z is already captured: turn the board to -Z", None));
    }
}
