//! A stream's clock: the unit of its time column (by its name, else by the rate it would give) and
//! the sample rate, from the timestamps, else from when the lines arrived, else as given.

use crate::limits::{MAX_GLITCH_RUN, PLAUSIBLE_HZ, RATE_AGREEMENT};
use serde::Serialize;

/// Where a stream's rate comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum RateSource {
    /// The stream's own time column.
    Timestamps,
    /// When the lines arrived on the port (losses are invisible).
    ArrivalTimes,
    /// `--rate`.
    Given,
}

/// A stream's sample rate and where it comes from.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Rate {
    /// Samples per second.
    pub hz: f64,
    /// Where it comes from.
    pub source: RateSource,
}

/// Seconds per unit of a time column, by its name, when the name says.
pub(super) fn unit_by_name(name: &str) -> Option<f64> {
    let name = name.to_ascii_lowercase();
    match () {
        _ if name.contains("[ns]") || name.contains("nano") => Some(1e-9),
        _ if name.contains("micro") || name == "us" || name.ends_with("_us") || name.contains("[us]") => Some(1e-6),
        _ if name.contains("milli") || name == "ms" || name.ends_with("_ms") || name.contains("[ms]") => Some(1e-3),
        _ if name.ends_with("_s") || name.contains("[s]") => Some(1.0),
        _ => None,
    }
}

/// Seconds per unit of a time column whose name does not say: the largest of s, ms, us, ns that
/// gives a plausible rate for the median step between lines.
pub(super) fn unit_by_steps(times: &[f64]) -> Option<f64> {
    let step = median_step(times)?;
    [1.0, 1e-3, 1e-6, 1e-9].into_iter().find(|unit| {
        let hz = 1.0 / (step * unit);
        (PLAUSIBLE_HZ.0..=PLAUSIBLE_HZ.1).contains(&hz)
    })
}

/// The median step between successive times (positive steps only), in their unit.
pub fn median_step(times: &[f64]) -> Option<f64> {
    let mut steps: Vec<f64> = times.windows(2).map(|w| w[1] - w[0]).filter(|s| *s > 0.0).collect();
    if steps.is_empty() {
        return None;
    }
    steps.sort_by(f64::total_cmp);
    Some(steps[steps.len() / 2])
}

/// The rate of samples at `times` seconds: one over the median step (robust to the odd lost or
/// late line).
pub fn rate_of(times: &[f64], source: RateSource) -> Option<Rate> {
    median_step(times).map(|step| Rate { hz: 1.0 / step, source })
}

/// Whether a rate someone gives agrees with the one a file shows, within [`RATE_AGREEMENT`].
pub fn agrees(given_hz: f64, shown_hz: f64) -> bool {
    (given_hz - shown_hz).abs() <= RATE_AGREEMENT * shown_hz
}

/// The rate of a stream: `--rate` (`given_hz`) must agree with its timestamps and stands over the
/// lines' arrival, which a port's bursts blur; `Err` with both when it disagrees.
pub fn settle(shown: Option<Rate>, given_hz: Option<f64>) -> Result<Option<Rate>, (f64, f64)> {
    let given = given_hz.map(|hz| Rate { hz, source: RateSource::Given });
    match (shown, given) {
        (Some(shown), Some(given)) if shown.source == RateSource::Timestamps && !agrees(given.hz, shown.hz) => {
            Err((given.hz, shown.hz))
        }
        (Some(shown), _) if shown.source == RateSource::Timestamps => Ok(Some(shown)),
        (shown, given) => Ok(given.or(shown)),
    }
}

/// Samples lost in gaps of the clock: a step between two times in sequence longer than the samples
/// between them by over half a period hides round(step / period) less those samples. A short run of
/// times out of sequence (garbled on their lines) is passed over, not taken for a gap.
pub fn lost_in_gaps(times: &[f64], rate: Rate) -> usize {
    let period = 1.0 / rate.hz;
    let hidden = |(i, a): (usize, f64), (j, b): (usize, f64)| {
        let (steps, between) = ((b - a) / period, (j - i) as f64);
        if steps > between + mutant!("stream-single-lost-uncounted", 0.5, 1.5) {
            (steps.round() - between) as usize
        } else {
            0
        }
    };
    in_sequence(times, period).windows(2).map(|w| hidden(w[0], w[1])).sum()
}

/// The times (with their indices) without those out of sequence on their own lines: a run of up to
/// [`MAX_GLITCH_RUN`] times outside the step from the one before to the one after it (one time out
/// of sequence is such a run). A clock that jumps stays jumped.
fn in_sequence(times: &[f64], period: f64) -> Vec<(usize, f64)> {
    let mut kept: Vec<(usize, f64)> = Vec::with_capacity(times.len());
    let mut i = 0;
    while i < times.len() {
        match kept.last().and_then(|&last| glitched_run(times, i, last, period)) {
            Some(run) => i += run,
            None => {
                kept.push((i, times[i]));
                i += 1;
            }
        }
    }
    kept
}

/// How many times from index `i` on are garbled, the last time kept being `before` at index `at`;
/// none when the time at `i` is in step with it, or is where the clock jumped to and stays.
fn glitched_run(times: &[f64], i: usize, (at, before): (usize, f64), period: f64) -> Option<usize> {
    // NOTE: in step: later than `before`, by no more than the samples between and half a period.
    let in_step = |j: usize| before < times[j] && times[j] - before <= ((j - at) as f64 + 0.5) * period;
    if in_step(i) {
        return None;
    }
    // NOTE: the run ends where the clock goes on past `before` with every time of the run outside
    // the step to there (a clock that jumped and stays has its jump inside it), or back in step.
    let outside = |j: usize| times[i..j].iter().all(|&t| t <= before || t > times[j]);
    let back = |j: usize| in_step(j) || (before < times[j] && outside(j));
    (i + 1..times.len().min(i + 1 + MAX_GLITCH_RUN)).find(|&j| back(j)).map(|j| j - i)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_time_columns_unit_comes_from_its_name_else_from_a_plausible_rate() {
        assert_eq!(unit_by_name("millis"), Some(1e-3));
        assert_eq!(unit_by_name("#timestamp [ns]"), Some(1e-9));
        assert_eq!(unit_by_name("t"), None);
        assert_eq!(unit_by_steps(&[1000.0, 1010.0, 1020.0]), Some(1e-3));
        assert_eq!(unit_by_steps(&[0.0, 0.01, 0.02]), Some(1.0));
        assert_eq!(unit_by_steps(&[0.0, 1e7, 2e7]), Some(1e-9));
        let rate = rate_of(&[0.0, 0.01, 0.02, 0.05, 0.06], RateSource::Timestamps).unwrap();
        assert!((rate.hz - 100.0).abs() < 1e-9);
        assert_eq!(lost_in_gaps(&[0.0, 0.01, 0.02, 0.05, 0.06], rate), 2);
    }

    #[test]
    fn a_single_lost_sample_is_counted_alone_and_after_another() {
        let rate = Rate { hz: 100.0, source: RateSource::Timestamps };
        // 1.02 missing: a step of two periods hides one sample.
        assert_eq!(lost_in_gaps(&[1.0, 1.01, 1.03, 1.04], rate), 1);
        // Two single losses apart.
        assert_eq!(lost_in_gaps(&[1.0, 1.02, 1.03, 1.05, 1.06], rate), 2);
    }

    #[test]
    fn a_given_rate_must_agree_with_the_timestamps_and_stands_over_the_arrival() {
        let stamped = Some(Rate { hz: 200.0, source: RateSource::Timestamps });
        assert_eq!(settle(stamped, Some(50.0)), Err((50.0, 200.0)));
        assert_eq!(settle(stamped, Some(201.0)), Ok(stamped));
        assert_eq!(settle(stamped, None), Ok(stamped));
        let arrived = Some(Rate { hz: 298.1, source: RateSource::ArrivalTimes });
        assert_eq!(settle(arrived, Some(100.0)), Ok(Some(Rate { hz: 100.0, source: RateSource::Given })));
        assert_eq!(settle(arrived, None), Ok(arrived));
    }

    #[test]
    fn a_single_time_out_of_sequence_is_a_glitch_not_a_gap_and_a_clock_that_jumps_stays_jumped() {
        let rate = Rate { hz: 100.0, source: RateSource::Timestamps };
        let back = [90.10, 90.11, 3.0, 90.12, 90.13];
        let ahead = [90.10, 90.11, 99999.0, 90.12, 90.13, 90.16];
        assert_eq!((lost_in_gaps(&back, rate), lost_in_gaps(&ahead, rate)), (0, 2));
        let kept = |times: &[f64]| in_sequence(times, 0.01).into_iter().map(|(_, t)| t).collect::<Vec<_>>();
        assert_eq!(kept(&ahead), vec![90.10, 90.11, 90.12, 90.13, 90.16]);
        // A board reset: millis start again, and stay started.
        assert_eq!(lost_in_gaps(&[50.0, 50.01, 0.0, 0.01, 0.02], rate), 0);
        assert_eq!(kept(&[50.0, 50.01, 0.0, 0.01, 0.02]).len(), 5);
        // A real gap that the clock keeps: 4 lost.
        assert_eq!(lost_in_gaps(&[1.0, 1.01, 1.06, 1.07], rate), 4);
    }

    #[test]
    fn a_short_run_of_garbled_times_invents_no_loss_and_a_clock_that_jumps_and_stays_still_counts() {
        let rate = Rate { hz: 100.0, source: RateSource::Timestamps };
        // Two garbled lines in a row, added between samples or in place of two samples' times.
        assert_eq!(lost_in_gaps(&[90.10, 90.11, 3.0, 4.0, 90.12, 90.13], rate), 0);
        assert_eq!(lost_in_gaps(&[90.10, 90.11, 3.0, 4.0, 90.14, 90.15], rate), 0);
        assert_eq!(lost_in_gaps(&[90.10, 90.11, 99999.0, 99999.01, 99999.02, 90.12, 90.13], rate), 0);
        // A sample late by 0.6 of a period, the next on time: none lost.
        assert_eq!(lost_in_gaps(&[1.0, 1.01, 1.026, 1.03, 1.04], rate), 0);
        // A real gap, kept by the clock: the samples hidden in it are lost, also after a glitch (whose
        // two lines are samples, their times garbled: 2 of the 4 the gap spans).
        assert_eq!(lost_in_gaps(&[1.0, 1.01, 1.06, 1.07, 1.08], rate), 4);
        assert_eq!(lost_in_gaps(&[1.0, 1.01, 3.0, 4.0, 1.06, 1.07, 1.08], rate), 2);
        // A clock that jumps far ahead and stays there: every step of the jump is lost.
        let jumped = lost_in_gaps(&[90.10, 90.11, 190.11, 190.12, 190.13, 190.14], rate);
        assert_eq!(jumped, 9_999);
    }
}
