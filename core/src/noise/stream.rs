//! A sketch's raw stream as a noise recording: the longest still period of the stream, in g and
//! deg/s, at the rate its timestamps give (or `--rate`); a stream with neither is refused, since a
//! rate guessed would scale every noise term.

use super::RateSeries;
use crate::limits::NOISE_MIN_SAMPLES;
use crate::stream::{Segment, StillPeriods, StreamLog};

/// Why a stream holds no still record to analyse.
#[derive(Debug, thiserror::Error)]
pub enum StillRecordError {
    #[error("{samples} samples is too few for an Allan deviation: record at least {NOISE_MIN_SAMPLES}")]
    TooShort { samples: usize },
    #[error("the stream has no timestamps, so its rate is unknown and every noise term would scale with a guess: give --rate (samples per second)")]
    NoStreamRate,
    #[error(
        "the stream has no gyro; the noise analysis takes both sensors (a recording of accelcal's own stream has them)"
    )]
    NoStreamGyro,
}

/// The longest still period of `log`, and the series the analysis takes from it.
pub fn longest_still(log: &StreamLog) -> Result<(Segment, RateSeries), StillRecordError> {
    let rate = log.rate.ok_or(StillRecordError::NoStreamRate)?;
    let gyro = log.gyro_dps().ok_or(StillRecordError::NoStreamGyro)?;
    let accel = log.accel_g();
    let still = StillPeriods::of(log);
    let longest =
        still.segments.into_iter().max_by_key(|s| s.samples).ok_or(StillRecordError::TooShort { samples: 0 })?;
    if longest.samples < NOISE_MIN_SAMPLES {
        return Err(StillRecordError::TooShort { samples: longest.samples });
    }
    let mut axes: [Vec<f64>; 6] = Default::default();
    for i in longest.first..=longest.last {
        let values = accel[i].iter().chain(&gyro[i]);
        axes.iter_mut().zip(values).for_each(|(axis, &value)| axis.push(value));
    }
    Ok((longest, RateSeries { rate_hz: rate.hz, axes, board: None }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fit::{FitOptions, Model, ModelChoice};
    use crate::report::stream::{json, StreamReport};
    use crate::sim::person::PersonSession;
    use crate::sim::sketch::Sketch;
    use crate::stream::StreamOptions;

    #[test]
    fn a_streams_rate_in_json_is_the_millihertz_number_the_text_shows() {
        let session = PersonSession::new(5, Sketch::Csv.reading());
        let text: String = Sketch::Csv.lines(&session).into_iter().map(|l| l.text).collect();
        let log = StreamLog::parse(&text, &StreamOptions::default()).unwrap();
        // NOTE: millis timestamps give 1 / 0.010000000000000002 s: the float's digits the JSON must not show.
        let hz = log.rate.unwrap().hz;
        assert!(hz != 100.0 && (hz - 100.0).abs() < 1e-9, "{hz}");
        let (_, series) = longest_still(&log).unwrap();
        let noise: serde_json::Value =
            serde_json::from_str(&crate::noise::json::render(&crate::noise::analyse(&series))).unwrap();
        assert_eq!(noise["sample_rate_hz"].as_f64(), Some(100.0), "{}", noise["sample_rate_hz"]);
        let report = StreamReport::new(&log, ModelChoice::Only(Model::Ortho9), &FitOptions::default()).unwrap();
        let fit: serde_json::Value = serde_json::from_str(&json(&report)).unwrap();
        assert_eq!(fit["rate_hz"].as_f64(), Some(100.0), "{}", fit["rate_hz"]);
    }
}
