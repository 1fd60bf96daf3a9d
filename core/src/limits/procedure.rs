//! The thresholds of a calibration session: how often a capture is tried, how long it lasts and
//! rests first, when the adaptive session may end, and the limits of the commands around it.

use std::time::Duration;

/// Captures of a position tried before giving up on a board that keeps moving.
///
/// NOTE: a bump or two while a person holds the board is common and costs a retry each; five moved
/// captures in a row is a board that cannot rest where it is, and the person is told so rather
/// than kept waiting.
pub const CAPTURE_ATTEMPTS: usize = 5;

/// Fewest positions before the prediction may end the session: the nine parameters and one more,
/// so that the fit has a residual to check itself by.
pub const MIN_ADAPTIVE_POSITIONS: usize = 10;

/// Shortest capture, in seconds.
///
/// NOTE: half a second holds 50 samples at 100 Hz: enough for a scatter to judge motion by (the
/// chip's motion check), and short next to the 1.5-2 s a person takes to turn the board.
pub const MIN_CAPTURE_SECONDS: f64 = 0.5;

/// Longest capture, in seconds: beyond it a drifting sensor's mean stops meaning one temperature.
pub const MAX_CAPTURE_SECONDS: f64 = 8.0;

/// How long, in seconds, the board must rest where it should after the prompt before it counts.
///
/// NOTE: a person needs a moment to read the instruction, and a board already lying on a face (or
/// put down and still settling) must not be captured at once: two seconds of accepted windows in a
/// row, after the prompt, since the windows start only then.
pub const SETTLE_SECONDS: f64 = 2.0;

/// How long the board must rest before a capture that stops by its rule starts, in seconds.
///
/// NOTE: shorter than the guided procedure's 2 s: such a capture refuses a board that still moves
/// (the chip's scatter check) and a mean away from the position (the tilt check), and a person told
/// the next position once needs no time to read it again.
pub const GOAL_SETTLE_SECONDS: f64 = 0.5;

/// Attempts before the self-test gives up on a board that keeps moving.
///
/// NOTE: an attempt is three phases of 200 samples (3 s at 200 Hz), so one bump spoils one attempt;
/// three spoiled in a row say the board is not resting.
pub const SELF_TEST_ATTEMPTS: u8 = 3;

/// How long the tool waits for the simulated board (which it turns itself) to reach and settle at a
/// position, as `calibrate --sim` allows.
///
/// NOTE: the simulated hand reaches a reachable position within seconds; a run that has not after a
/// minute never will (the measurements of [`super::MAX_PLACEMENT_DEG`] waited 60 s and failed).
pub const SIM_WAIT_LIMIT: Duration = Duration::from_secs(60);

/// The default target, in mg: the error the 9-parameter fit reaches at fresh orientations on a
/// settled sensor with about 18 s of averaging in all (issue 16's measurement).
pub const DEFAULT_TARGET_MG: f64 = 0.2;

/// `calibrate --quick`'s target, in mg. Measured on the simulated board (seeds 1-5, issue 40): at
/// 1 mg and at 0.5 mg each capture already stops at its shortest, 31 s of board time against 55-57 s
/// for the default, and the verified error was 0.49-1.12 mg, so 1 mg was missed at 2 of 5 seeds; 2 mg
/// is reached at every seed in the same time.
pub const QUICK_TARGET_MG: f64 = 2.0;

/// Longest recording, in seconds.
///
/// NOTE: a day at 1 kHz is 86.4 million samples, within the stream's u32 sample count.
pub const MAX_RECORD_SECONDS: i64 = 24 * 3600;
