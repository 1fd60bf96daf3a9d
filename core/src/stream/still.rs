//! A stream's still periods as the data set a fit takes: one row per segment, its mean in the
//! stream's own unit (so the calibration applies to the values as the sketch prints them), its
//! sample count and scatter, and the gyro's mean; and the gyro's bias from them. Periods at fresh
//! orientations (away from every face and corner, [`super::guide::trains`]) are held out to verify
//! the calibration, when enough others remain to fit it.

use serde::Serialize;

use super::log::StreamLog;
use super::segment::{segment, Segment, Stillness};
use crate::data::{Dataset, Row};
use crate::limits::MIN_TRAINING_PERIODS;

/// A segment as the report lists it: its lines in the stream, and its scatter.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SegmentLines {
    /// The stream's lines of its first and last sample.
    pub first_line: usize,
    pub last_line: usize,
    /// Samples averaged.
    pub samples: usize,
    /// The accelerometer's scatter, the rms over its axes of the standard deviation, in mg.
    pub scatter_mg: f64,
    /// Whether it verifies the calibration (a fresh orientation, held out of the fit).
    pub verifies: bool,
}

/// A stream's still periods.
#[derive(Debug, Clone)]
pub struct StillPeriods {
    /// The segments, sample indices into the log.
    pub segments: Vec<Segment>,
    /// The segments by line.
    pub lines: Vec<SegmentLines>,
    /// The rows a fit takes.
    pub dataset: Dataset,
    /// The rows held out to verify it (fresh orientations).
    pub held_out: Dataset,
}

impl StillPeriods {
    /// Finds and averages the still periods of `log`.
    pub fn of(log: &StreamLog) -> Self {
        let gyro = log.gyro_dps();
        let segments = segments_of(&log.accel_g(), gyro.as_deref(), log.rate.map(|r| r.hz));
        let per_g = log.accel_unit.per_g();
        let trains: Vec<bool> = segments.iter().map(|s| super::guide::trains(s.mean_g)).collect();
        let hold_out = trains.iter().filter(|&&t| t).count() >= MIN_TRAINING_PERIODS;
        let verifies: Vec<bool> = trains.iter().map(|&t| hold_out && !t).collect();
        let (mut dataset, mut held_out) = (Dataset { rows: Vec::new() }, Dataset { rows: Vec::new() });
        for (segment, &verifying) in segments.iter().zip(&verifies) {
            let rows = if verifying { &mut held_out.rows } else { &mut dataset.rows };
            rows.push(row(log, segment, per_g));
        }
        let lines = segments.iter().zip(&verifies).map(|(s, &v)| segment_lines(log, s, v)).collect();
        StillPeriods { segments, lines, dataset, held_out }
    }

    /// The gyro's bias in deg/s: its mean over every still sample.
    pub fn gyro_bias_dps(&self) -> Option<[f64; 3]> {
        let total: usize = self.segments.iter().map(|s| s.samples).sum();
        let weighted = |k: usize| -> Option<f64> {
            let sum: Option<f64> = self.segments.iter().map(|s| s.gyro_mean_dps.map(|g| g[k] * s.samples as f64)).sum();
            sum.map(|sum| sum / total.max(1) as f64)
        };
        Some([weighted(0)?, weighted(1)?, weighted(2)?])
    }
}

/// The still periods at the stream's rate; without one, those of windows that suit 10-100 Hz,
/// unless the windows of a slow sketch (2-10 Hz: Adafruit's `basic_readings` prints every 500 ms)
/// find more, which they do only when the stream is that slow.
fn segments_of(accel_g: &[[f64; 3]], gyro_dps: Option<&[[f64; 3]]>, rate_hz: Option<f64>) -> Vec<Segment> {
    let segments = segment(accel_g, gyro_dps, &Stillness::for_rate(rate_hz));
    if rate_hz.is_some() || segments.len() >= MIN_TRAINING_PERIODS {
        return segments;
    }
    let slow = segment(accel_g, gyro_dps, &Stillness::SLOW);
    if slow.len() > segments.len() {
        slow
    } else {
        segments
    }
}

fn row(log: &StreamLog, segment: &Segment, per_g: f64) -> Row {
    Row {
        line: log.samples[segment.first].line,
        reading: segment.mean_g.map(|v| v * per_g),
        reference: None,
        count: u32::try_from(segment.samples).ok(),
        std: Some(segment.std_g.map(|v| v * per_g)),
        temp_c: None,
        gyro_mean_dps: segment.gyro_mean_dps,
    }
}

fn segment_lines(log: &StreamLog, segment: &Segment, verifies: bool) -> SegmentLines {
    let rms = (segment.std_g.iter().map(|v| v * v).sum::<f64>() / 3.0).sqrt();
    SegmentLines {
        first_line: log.samples[segment.first].line,
        last_line: log.samples[segment.last].line,
        samples: segment.samples,
        scatter_mg: rms * 1e3,
        verifies,
    }
}
