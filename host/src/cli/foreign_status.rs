//! What a person calibrating from their board's own stream is told once a second: the stream, how
//! the board rests and which way is up, how much longer to hold the current position (until its
//! mean is known to what `--target-mg` needs, from the scatter measured in it), and which way to
//! turn next; the session is saved whenever a still period was added, and the run ends once every
//! face and corner is rested and enough fresh orientations are held to verify the fit.

use super::args::CalibrateArgs;
use super::foreign_session::Kept;
use super::length::ADAPTIVE_VERIFY_POSITIONS;
use crate::error::Error;
use crate::limits::MAX_CAPTURE_SECONDS;
use crate::limits::MOVING_SCATTER_G;
use crate::procedure::stop_rule::{Noise, StopRule};
use crate::stream::guide::{all_rested, nearest_name, next_turn};
use crate::stream::live::LiveStream;
use crate::stream::plausible::gyro_doubt;
use crate::stream::segment::{mean_std, Segment, Stillness};
use crate::stream::{read_heard, StillPeriods, StreamError, StreamLog, StreamOptions};

/// Where the session stands between status lines.
pub(super) struct Progress {
    /// Still periods when the session was last saved.
    saved_periods: usize,
    /// Fresh orientations wanted to verify the fit.
    verify: usize,
    /// The standard error each axis' mean should reach, in g.
    want_g: f64,
}

impl Progress {
    /// Nothing saved yet, the verification and the target as `args` ask.
    pub fn new(args: &CalibrateArgs) -> Self {
        let rule = StopRule { target_mg: args.length.target_mg, noise: Noise::Measured, rate_hz: 0 };
        let verify = usize::from(args.verify.unwrap_or(ADAPTIVE_VERIFY_POSITIONS));
        Progress { saved_periods: 0, verify, want_g: rule.mean_std_g() }
    }
}

/// Tells the person where things stand and keeps the session; `Some` with why once done.
pub(super) fn status(
    live: &LiveStream,
    options: &StreamOptions,
    kept: &Kept,
    progress: &mut Progress,
) -> Result<Option<String>, Error> {
    let log = match read_heard(live.lines(), options) {
        Ok(log) => log,
        Err(unit @ (StreamError::OtherAccelUnit { .. } | StreamError::BeyondReach { .. })) => {
            return Ok(Some(unit.to_string()))
        }
        Err(_) => return Ok(None),
    };
    let still = StillPeriods::of(&log);
    // NOTE: only while no period rests: a gyro read in the wrong unit rests nowhere.
    if let Some(doubt) = still.segments.is_empty().then(|| gyro_doubt(&log)).flatten() {
        return Ok(Some(doubt));
    }
    eprintln!("{}", status_line(&log, &still, progress.want_g));
    if still.segments.len() != progress.saved_periods {
        progress.saved_periods = still.segments.len();
        kept.save(&log, None)?;
    }
    let trained: Vec<[f64; 3]> = still.dataset.rows.iter().map(|r| r.reading).collect();
    let fresh = still.held_out.rows.len();
    Ok((all_rested(&trained) && fresh >= progress.verify)
        .then(|| format!("every face and corner rested and {fresh} fresh orientations held")))
}

/// One status line: the stream, the board's rest and tilt, the position being held, the next turn.
fn status_line(log: &StreamLog, still: &StillPeriods, want_g: f64) -> String {
    let accel = log.accel_g();
    let (up, scatter) = mean_std(&accel[accel.len().saturating_sub(5)..]);
    let moving = scatter.iter().any(|&s| s > MOVING_SCATTER_G);
    let tilt = up.map(|v| v / shared::linalg::norm(up));
    let rested: Vec<[f64; 3]> = still.segments.iter().map(|s| s.mean_g).collect();
    let holding = if moving { None } else { holding(log, still, want_g) };
    format!(
        "{} {:.1} Hz: {} samples, {} still periods ({} fresh); {}, up = ({:+.2} {:+.2} {:+.2}); {}",
        log.layout.dialect.name(),
        log.rate.map_or(0.0, |r| r.hz),
        log.samples.len(),
        rested.len(),
        still.held_out.rows.len(),
        if moving { "moving" } else { "resting" },
        tilt[0],
        tilt[1],
        tilt[2],
        holding.unwrap_or_else(|| next_turn(up, &rested))
    )
}

/// The position being held, when the board rests in a still period: how much longer to hold it,
/// or, once its mean is known to `want_g` per axis (or held [`MAX_CAPTURE_SECONDS`]), where to turn next.
fn holding(log: &StreamLog, still: &StillPeriods, want_g: f64) -> Option<String> {
    let hz = log.rate?.hz;
    let segment = current(log, still, hz)?;
    let n = segment.samples as f64;
    let worst_std = segment.std_g.iter().copied().fold(0.0, f64::max);
    let known_mg = worst_std / n.sqrt() * 1e3;
    let name = nearest_name(segment.mean_g);
    let (held_s, needed_s) = (n / hz, ((worst_std / want_g).powi(2) / hz).min(MAX_CAPTURE_SECONDS));
    let wanted = format!("its mean known to {known_mg:.3} mg, {:.3} mg wanted", want_g * 1e3);
    let rested: Vec<[f64; 3]> = still.segments.iter().map(|s| s.mean_g).collect();
    Some(match (known_mg <= want_g * 1e3, held_s >= needed_s) {
        (true, _) => format!("{name} taken ({wanted}); {}", next_turn(segment.mean_g, &rested)),
        (false, true) => format!(
            "{name} taken after {held_s:.1} s ({wanted}: this stream's noise allows no better in {MAX_CAPTURE_SECONDS} s); {}",
            next_turn(segment.mean_g, &rested)
        ),
        (false, false) => format!("{name}: hold it still {:.1} s more ({wanted})", needed_s - held_s),
    })
}

/// The still period the board rests in now: the last one, when it reaches the latest samples.
fn current<'a>(log: &StreamLog, still: &'a StillPeriods, hz: f64) -> Option<&'a Segment> {
    let segment = still.segments.last()?;
    let reach = Stillness::for_rate(Some(hz)).trim + 2;
    (segment.last + reach >= log.samples.len()).then_some(segment)
}
