//! Still periods in a run of samples, each averaged: the one home for telling rest from motion in a
//! stream (a saved log for `fit` and `noise`, a live stream for `calibrate`).
//!
//! A sample rests when the accelerometer's scatter over a short window around it is near the
//! stream's typical scatter (most of a calibration session rests, so the median window is a still
//! one), and, with a gyro, when the gyro reads within a few deg/s of its median (its bias). A run of
//! resting samples, a few trimmed at each end, long enough, is a segment. Samples caught at the very
//! start or end of a turn do little harm: every sample reads 1 g, so a mixture only shortens the
//! mean by the square of the angle.

use crate::limits::{MIN_STILL_SEGMENT_S, STILL_SCATTER_FACTOR, STILL_SCATTER_FLOOR_G, STREAM_GYRO_STILL_DPS};
use serde::Serialize;
use shared::linalg::{norm, sub};

/// How a stream's rest is told apart from motion, in samples.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stillness {
    /// The window over which the accelerometer's scatter is judged.
    pub window: usize,
    /// Fewest samples in a segment, after trimming.
    pub min_samples: usize,
    /// Samples dropped at each end of a still run.
    pub trim: usize,
}

/// Window and trim in seconds, at a known rate.
const WINDOW_S: f64 = 0.5;
const TRIM_S: f64 = 0.1;

impl Stillness {
    /// The windows for a stream of unknown rate that is slow: 2-10 Hz (at 2 Hz, 10 samples are 5 s of
    /// a hold of 7 s or more, and a window of 5 spans a turn).
    pub const SLOW: Stillness = Stillness { window: 5, min_samples: 10, trim: 1 };

    /// The windows for a stream at `rate_hz`; without a rate, lengths that suit 10-100 Hz.
    pub fn for_rate(rate_hz: Option<f64>) -> Self {
        match rate_hz {
            Some(hz) => Stillness {
                window: ((WINDOW_S * hz).round() as usize).max(5),
                min_samples: ((MIN_STILL_SEGMENT_S * hz).round() as usize).max(10),
                trim: ((TRIM_S * hz).round() as usize).max(1),
            },
            None => Stillness { window: 9, min_samples: 15, trim: 1 },
        }
    }
}

/// One still period, averaged.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Segment {
    /// Index of its first and last sample.
    pub first: usize,
    pub last: usize,
    /// Samples averaged.
    pub samples: usize,
    /// The accelerometer's mean, in g.
    pub mean_g: [f64; 3],
    /// The accelerometer's standard deviation per axis, in g.
    pub std_g: [f64; 3],
    /// The gyro's mean, in deg/s, when there is a gyro.
    pub gyro_mean_dps: Option<[f64; 3]>,
}

/// The still periods of `accel_g` (and `gyro_dps`, same length, when there is a gyro).
pub fn segment(accel_g: &[[f64; 3]], gyro_dps: Option<&[[f64; 3]]>, stillness: &Stillness) -> Vec<Segment> {
    let mut still = accel_rests(accel_g, stillness.window);
    if let Some(gyro) = gyro_dps {
        let bias = median3(gyro);
        still.iter_mut().zip(gyro).for_each(|(s, g)| *s &= norm(sub(*g, bias)) <= STREAM_GYRO_STILL_DPS);
    }
    runs(&still)
        .into_iter()
        .filter_map(|(first, last)| trimmed(first, last, stillness))
        .map(|(first, last)| averaged(accel_g, gyro_dps, first, last))
        .collect()
}

/// Whether the accelerometer's scatter over the window centred on each sample is a still one's.
fn accel_rests(accel: &[[f64; 3]], window: usize) -> Vec<bool> {
    let scatter: Vec<f64> = (0..accel.len()).map(|i| window_scatter(accel, i, window)).collect();
    let mut sorted = scatter.clone();
    sorted.sort_by(f64::total_cmp);
    let limit =
        (STILL_SCATTER_FACTOR * sorted.get(sorted.len() / 2).copied().unwrap_or(0.0)).max(STILL_SCATTER_FLOOR_G);
    scatter.iter().map(|&s| s <= limit).collect()
}

/// The largest axis' standard deviation over the window centred on sample `i`.
fn window_scatter(accel: &[[f64; 3]], i: usize, window: usize) -> f64 {
    let start = i.saturating_sub(window / 2);
    let end = (start + window).min(accel.len());
    let (_, std) = mean_std(&accel[start..end]);
    std.into_iter().fold(0.0, f64::max)
}

/// The runs of `true`, as first and last index.
fn runs(flags: &[bool]) -> Vec<(usize, usize)> {
    let mut runs = Vec::new();
    let mut start = None;
    for (i, &flag) in flags.iter().chain([&false]).enumerate() {
        match (flag, start) {
            (true, None) => start = Some(i),
            (false, Some(first)) => {
                runs.push((first, i - 1));
                start = None;
            }
            _ => {}
        }
    }
    runs
}

fn trimmed(first: usize, last: usize, stillness: &Stillness) -> Option<(usize, usize)> {
    let (first, last) = (first + stillness.trim, last.checked_sub(stillness.trim)?);
    (last >= first && last - first + 1 >= stillness.min_samples).then_some((first, last))
}

fn averaged(accel: &[[f64; 3]], gyro: Option<&[[f64; 3]]>, first: usize, last: usize) -> Segment {
    let (mean_g, std_g) = mean_std(&accel[first..=last]);
    let gyro_mean_dps = gyro.map(|g| mean_std(&g[first..=last]).0);
    Segment { first, last, samples: last - first + 1, mean_g, std_g, gyro_mean_dps }
}

/// Mean and sample standard deviation per axis.
pub fn mean_std(values: &[[f64; 3]]) -> ([f64; 3], [f64; 3]) {
    let n = values.len().max(1) as f64;
    let mean = [0, 1, 2].map(|k| values.iter().map(|v| v[k]).sum::<f64>() / n);
    let spread = |k: usize| values.iter().map(|v| (v[k] - mean[k]).powi(2)).sum::<f64>() / (n - 1.0).max(1.0);
    (mean, [0, 1, 2].map(|k| spread(k).sqrt()))
}

/// The per-axis median.
pub fn median3(values: &[[f64; 3]]) -> [f64; 3] {
    [0, 1, 2].map(|k| {
        let mut axis: Vec<f64> = values.iter().map(|v| v[k]).collect();
        axis.sort_by(f64::total_cmp);
        axis.get(axis.len() / 2).copied().unwrap_or(0.0)
    })
}
