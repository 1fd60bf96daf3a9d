//! A live stream's lines read so far as a stream: its samples, and the rate at which those that are
//! samples arrived (a line dropped, a garbled value beyond the sensor's reach among them, is no
//! sample and is not counted in the rate).

use super::arrival::arrival_hz;
use super::log::{LineReader, StreamLog, StreamOptions};
use super::timing::{settle, Rate, RateSource};
use super::{DropReason, Dropped, Layout, StreamError};

/// The stream of `lines` (each line's text and its arrival, seconds), read with `options`, or why
/// not yet (its dialect or enough samples still to come) or not at all (a unit its values do not fit).
pub fn read_heard(lines: &[(String, f64)], options: &StreamOptions) -> Result<StreamLog, StreamError> {
    let layout = Layout::detect(lines.iter().map(|(text, _)| text.as_str()))?;
    let mut reader = LineReader::new(layout.clone());
    let (mut samples, mut dropped) = (Vec::new(), Dropped::default());
    for (index, (text, _)) in lines.iter().enumerate() {
        match reader.read(text) {
            Ok(sample) => samples.push(sample),
            Err(DropReason::Continued) => {}
            Err(reason) => dropped.add(reason, index + 1),
        }
    }
    let mut log = StreamLog::new(layout, samples, dropped, None, options)?;
    // NOTE: after StreamLog::new, whose samples are those it accepted: lines are 1-based.
    let arrivals: Vec<f64> = log.samples.iter().map(|s| lines[s.line - 1].1).collect();
    let arrived = arrival_hz(&arrivals).map(|hz| Rate { hz, source: RateSource::ArrivalTimes });
    // NOTE: a rate from arrival times never disagrees with --rate: it gives way to it.
    log.rate = settle(arrived, options.rate_hz).unwrap_or(log.rate);
    Ok(log)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_arrival_rate_counts_only_accepted_samples_not_lines_beyond_the_sensors_reach() {
        // 100 Hz of six counts a line; after every third sample a garbled line (a value beyond 16-bit
        // counts) arrives between two samples.
        let mut lines = Vec::new();
        for k in 0..300u32 {
            let at = 1.0 + f64::from(k) * 0.01;
            lines.push((format!("{} -{} {} 12 -7 3", 120 + k % 7, 40 + k % 5, 16_300 + k % 11), at));
            if k % 3 == 2 {
                lines.push((format!("120 -40 {} 12 -7 3", 9_999_999 + k), at + 0.005));
            }
        }
        let log = read_heard(&lines, &StreamOptions::default()).unwrap();
        assert_eq!((log.samples.len(), log.dropped.count(DropReason::BeyondRange)), (300, 100));
        let rate = log.rate.unwrap();
        assert_eq!(rate.source, RateSource::ArrivalTimes);
        assert!((rate.hz - 100.0).abs() < 0.2, "{} Hz", rate.hz);
    }
}
