//! What a person calibrating from their board's own stream is told once a second: the stream, how
//! the board rests and which way is up, how much longer to hold the current position (until its
//! mean is known to what the target needs, from the scatter measured in it), and which way to
//! turn next; whether a still period was added since the session was last kept, and whether the
//! run is done (every face and corner rested and enough fresh orientations held to verify the fit)
//! or refused (its values not in the unit they are read in). The run (`run::stream`) tells the
//! person and keeps the session.

use super::guide::{all_rested, nearest_name, next_turn};
use super::heard::read_heard;
use super::log::{StreamLog, StreamOptions};
use super::plausible::gyro_doubt;
use super::refusal::text_without_samples;
use super::segment::{mean_std, Segment, Stillness};
use super::still::StillPeriods;
use super::StreamError;
use crate::limits::{FRESH_WAIT_S, LIVE_REFUSAL_LINES, MAX_CAPTURE_SECONDS, MOVING_SCATTER_G};

/// Where a stream session stands between status lines.
#[derive(Debug, Clone, PartialEq)]
pub struct Progress {
    /// Still periods when the session was last kept.
    kept_periods: usize,
    /// Fresh orientations wanted to verify the fit.
    verify: usize,
    /// The standard error each axis' mean should reach, in g.
    want_g: f64,
    /// When the last new still period came, in seconds of arrival.
    added_at_s: f64,
}

/// What one look at the lines so far says.
#[derive(Debug, Clone, Default)]
pub struct Look {
    /// The status line to tell the person, once the lines read as a stream.
    pub line: Option<String>,
    /// The stream read so far, when it holds another still period since the session was last
    /// kept: the session to keep again.
    pub keep: Option<StreamLog>,
    /// Why the run ends now, when it does.
    pub ends: Option<Ends>,
}

/// Why a live stream session ends now: done, or refused as not the stream it is read as.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Ends {
    /// Every face and corner rested and enough fresh orientations held: complete, to be certified.
    Done(String),
    /// Its values are not in the unit they are read in: nothing it holds may be certified.
    Refused(String),
    /// Every face and corner rested, but the fresh orientations stopped coming short of those wanted:
    /// fitted with what it has, not certified.
    Stalled(String),
}

impl Progress {
    /// Nothing kept yet; each position held until its mean is known to `want_g` per axis (g), and
    /// `verify` fresh orientations wanted.
    pub fn new(want_g: f64, verify: usize) -> Self {
        Progress { kept_periods: 0, verify, want_g, added_at_s: 0.0 }
    }

    /// Looks at the lines so far (each with its arrival in seconds), read as `options` say.
    pub fn look(&mut self, lines: &[(String, f64)], options: &StreamOptions) -> Look {
        let log = match read_heard(lines, options) {
            Ok(log) => log,
            Err(error) => return Look { ends: refused(&error, lines), ..Look::default() },
        };
        let still = StillPeriods::of(&log);
        // NOTE: only while no period rests: a gyro read in the wrong unit rests nowhere.
        if let Some(doubt) = still.segments.is_empty().then(|| gyro_doubt(&log)).flatten() {
            return Look { ends: Some(Ends::Refused(doubt)), ..Look::default() };
        }
        let line = Some(status_line(&log, &still, self.want_g));
        let trained: Vec<[f64; 3]> = still.dataset.rows.iter().map(|r| r.reading).collect();
        let fresh = still.held_out.rows.len();
        let added = still.segments.len() != self.kept_periods;
        let now_s = lines.last().map_or(0.0, |(_, at)| *at);
        if added {
            (self.kept_periods, self.added_at_s) = (still.segments.len(), now_s);
        }
        let ends = match (all_rested(&trained), fresh >= self.verify) {
            (true, true) => {
                Some(Ends::Done(format!("every face and corner rested and {fresh} fresh orientations held")))
            }
            (true, false) if now_s - self.added_at_s > FRESH_WAIT_S => Some(Ends::Stalled(stalled(fresh, self.verify))),
            _ => None,
        };
        Look { line, keep: added.then_some(log), ends }
    }
}

/// Why the run ends on a stream not read (yet), when it does: a unit its values do not fit, or
/// [`LIVE_REFUSAL_LINES`] lines of text none of which is read (quoted, with the fix).
fn refused(error: &StreamError, lines: &[(String, f64)]) -> Option<Ends> {
    match error {
        StreamError::OtherAccelUnit { .. } | StreamError::BeyondReach { .. } => Some(Ends::Refused(error.to_string())),
        StreamError::NoData { .. } | StreamError::UnclearColumns { .. } | StreamError::UnclearUnit { .. }
            if lines.len() >= LIVE_REFUSAL_LINES && is_text(lines) =>
        {
            Some(Ends::Refused(format!("{} lines came and none was read: {error}", lines.len())))
        }
        _ => None,
    }
}

/// Whether the lines are text (bytes that are not are the wrong baud rate's, which the stream's
/// silence names).
fn is_text(lines: &[(String, f64)]) -> bool {
    let texts: Vec<&str> = lines.iter().map(|(text, _)| text.as_str()).collect();
    text_without_samples(&texts).is_some()
}

/// Why a session whose fresh orientations stopped coming ends, and what it means.
fn stalled(fresh: usize, verify: usize) -> String {
    format!(
        "every face and corner rested but only {fresh} of the {verify} fresh orientations wanted were held, and no \
         still period came in {FRESH_WAIT_S:.0} s: the calibration is fitted with what was held and not certified; \
         to finish it, resume the session and hold the board still between two faces (an edge) {} more time{}",
        verify - fresh,
        if verify - fresh == 1 { "" } else { "s" }
    )
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::person::PersonSession;
    use crate::sim::sketch::Sketch;
    use crate::stream::AccelUnit;

    /// A simulated person's three-minute session as the CSV sketch prints it, each line with its time.
    fn heard() -> Vec<(String, f64)> {
        let person = PersonSession::new(2, Sketch::Csv.reading());
        let lines = Sketch::Csv.lines(&person).into_iter();
        lines.map(|line| (line.text.trim_end_matches(['\r', '\n']).to_owned(), line.at_s)).collect()
    }

    #[test]
    fn the_session_is_kept_once_per_new_still_period_and_ends_once_every_position_and_the_fresh_ones_are_held() {
        let (lines, options) = (heard(), StreamOptions::default());
        let mut progress = Progress::new(1e-4, 4);
        let first = progress.look(&lines, &options);
        let line = first.line.expect("a status line");
        assert!(line.starts_with("csv 100.0 Hz: ") && line.contains("4 fresh"), "{line}");
        assert!(first.keep.is_some(), "the still periods found were not kept");
        let done = Some(Ends::Done("every face and corner rested and 4 fresh orientations held".to_owned()));
        assert_eq!(first.ends, done);
        // The same lines again: no still period more, nothing to keep again.
        let again = progress.look(&lines, &options);
        assert!(again.keep.is_none() && again.line.is_some(), "kept again with no new still period");
        // A fifth fresh orientation wanted: the person's four edges do not end the run.
        assert_eq!(Progress::new(1e-4, 5).look(&lines, &options).ends, None);
    }

    #[test]
    fn a_stream_read_in_another_unit_is_refused_naming_it_and_keeps_nothing() {
        let options = StreamOptions { accel_unit: Some(AccelUnit::G), ..StreamOptions::default() };
        let look = Progress::new(1e-4, 4).look(&heard(), &options);
        assert!(look.line.is_none() && look.keep.is_none(), "{look:?}");
        let Some(Ends::Refused(why)) = look.ends else { panic!("not refused: {:?}", look.ends) };
        assert!(why.contains("give --input-unit counts-2g"), "{why}");
    }
}
