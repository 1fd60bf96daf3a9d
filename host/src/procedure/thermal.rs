//! Learning how the sensor drifts: the board rests while its temperature changes (warm-up, a cool
//! or warm place), the chip averages every sample of its captures into 1 degC bins, the host keeps
//! them per orientation, and learning stops when the span is enough or the temperature stalls. The bins belong to the caller, so a run that is
//! interrupted keeps what it learned; [`kept`] keeps them on disk as they are learned. [`learned`]
//! shows the learning and fits the model it learned on any board; [`resting`] is a person's run
//! (`accelcal thermal --port`); the simulated story (`--sim`) is `sim::thermal`'s.

use std::collections::BTreeMap;

use shared::linalg::Vec3;
use shared::protocol::{CalibrationSlot, CaptureStats, TempBin};

use super::ProcedureError;
use crate::fit::thermal::ThermalPoint;
use crate::limits::{MIN_THERMAL_SPAN_C, THERMAL_STALL_C, THERMAL_STALL_ROUNDS};
use crate::link::{Connection, LinkError};

/// Width of a temperature bin, in degC.
const BIN_C: f64 = 1.0;

/// The learned averages: per (temperature bin, orientation), the running mean of the captures.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ThermalBins {
    bins: BTreeMap<(i64, usize), (usize, ThermalPoint)>,
    low_c: Option<f64>,
    high_c: Option<f64>,
}

impl ThermalBins {
    /// Adds one capture taken resting on `force_g` (orientation number `face`), weighted by its samples.
    pub fn add(&mut self, face: usize, force_g: Vec3<f64>, stats: &CaptureStats) {
        let point = ThermalPoint {
            temp_c: f64::from(stats.temp_c),
            force_g,
            accel_g: stats.mean_g.map(f64::from),
            gyro_dps: stats.gyro_mean_dps.map(f64::from),
        };
        self.add_point(face, point, stats.samples);
    }

    /// Adds one of the chip's temperature bins, taken resting on `force_g` (orientation `face`).
    pub fn add_chip_bin(&mut self, face: usize, force_g: Vec3<f64>, bin: &TempBin) {
        let point = ThermalPoint {
            temp_c: f64::from(bin.temp_c),
            force_g,
            accel_g: bin.accel_g.map(f64::from),
            gyro_dps: bin.gyro_dps.map(f64::from),
        };
        self.add_point(face, point, bin.samples);
    }

    /// Adds `samples` samples averaging `point` to the bin of its degree and orientation.
    fn add_point(&mut self, face: usize, point: ThermalPoint, samples: u32) {
        let temp_c = point.temp_c;
        let key = ((temp_c / BIN_C).floor() as i64, face);
        let entry = self.bins.entry(key).or_insert((0, point));
        entry.0 += samples as usize;
        let weight = f64::from(samples) / entry.0.max(1) as f64;
        let mean = |old: f64, new: f64| old + (new - old) * weight;
        entry.1.temp_c = mean(entry.1.temp_c, point.temp_c);
        entry.1.accel_g = [0, 1, 2].map(|k| mean(entry.1.accel_g[k], point.accel_g[k]));
        entry.1.gyro_dps = [0, 1, 2].map(|k| mean(entry.1.gyro_dps[k], point.gyro_dps[k]));
        self.low_c = Some(self.low_c.map_or(temp_c, |low| low.min(temp_c)));
        self.high_c = Some(self.high_c.map_or(temp_c, |high| high.max(temp_c)));
    }

    /// Every bin: its orientation number, samples and average.
    fn entries(&self) -> impl Iterator<Item = (usize, usize, &ThermalPoint)> {
        self.bins.iter().map(|((_, face), (samples, point))| (*face, *samples, point))
    }

    /// The bin averages, for the fit.
    pub fn points(&self) -> Vec<ThermalPoint> {
        self.bins.values().map(|(_, point)| *point).collect()
    }

    /// Number of bins filled.
    pub fn len(&self) -> usize {
        self.bins.len()
    }

    /// Whether nothing was learned.
    pub fn is_empty(&self) -> bool {
        self.bins.is_empty()
    }

    /// Lowest and highest temperature seen, in degC.
    pub fn range_c(&self) -> Option<(f64, f64)> {
        self.low_c.zip(self.high_c)
    }

    /// Highest minus lowest temperature seen, in degC.
    pub fn span_c(&self) -> f64 {
        self.range_c().map_or(0.0, |(low, high)| high - low)
    }

    /// The bins, or why they cannot make a temperature model: a span under 10 degC.
    pub fn check_span(&self) -> Result<&Self, ProcedureError> {
        let (low_c, high_c) = self.range_c().unwrap_or((0.0, 0.0));
        if self.span_c() < MIN_THERMAL_SPAN_C {
            return Err(ProcedureError::SpanTooSmall { low_c, high_c, needed_c: MIN_THERMAL_SPAN_C });
        }
        Ok(self)
    }
}

/// What the board does between captures: for the simulated board, the tool turns it and lets time
/// pass; a person's board rests where it is while real time passes.
pub trait ThermalBoard {
    /// Rests the board on orientation number `face` (a person's board stays where it is).
    fn place(&mut self, force_g: Vec3<f64>) -> Result<(), ProcedureError>;
    /// Lets `seconds` pass between rounds of captures.
    fn rest(&mut self, seconds: f64) -> Result<(), ProcedureError>;
}

/// How a learning run goes.
#[derive(Debug, Clone)]
pub struct LearnOptions {
    /// The orientations captured each round (one: offset only; several: sensitivity too).
    pub faces: Vec<Vec3<f64>>,
    /// Capture length, in seconds.
    pub capture_seconds: u8,
    /// Rest between rounds, in seconds.
    pub rest_seconds: f64,
    /// Stop when the temperature has spanned this much, in degC.
    pub target_span_c: f64,
    /// Stop after this many rounds at most.
    pub max_rounds: usize,
}

/// Why learning stopped (when it was not interrupted).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LearnEnd {
    /// The temperature spanned the target.
    SpanReached,
    /// The temperature stopped changing.
    Stalled,
    /// The round limit was reached.
    RoundLimit,
}

/// What the live display shows after each capture.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LearnStatus {
    /// The latest capture's temperature, in degC.
    pub temp_c: f64,
    /// Span so far, in degC.
    pub span_c: f64,
    /// Bins filled.
    pub bins: usize,
    /// Degrees the chip's bins spanned in the latest capture.
    pub chip_bins: usize,
}

/// What the caller does after each capture with the status and the bins so far (show them, keep
/// them on disk); an error stops the learning.
pub type OnStatus<'a> = &'a mut dyn FnMut(LearnStatus, &ThermalBins) -> Result<(), ProcedureError>;

/// Learns into `bins` until the span is reached or the temperature stalls; an error leaves the bins
/// learned so far in place.
pub fn learn(
    connection: &mut Connection,
    board: &mut dyn ThermalBoard,
    options: &LearnOptions,
    bins: &mut ThermalBins,
    on_status: OnStatus,
) -> Result<LearnEnd, ProcedureError> {
    let mut history: Vec<f64> = Vec::new();
    // NOTE: the chip's bins hold every sample since they were last taken (earlier captures too).
    connection.client.take_temperature_bins()?;
    for _ in 0..options.max_rounds {
        let temp_c = learn_round(connection, board, options, bins, on_status)?;
        history.push(temp_c);
        if bins.span_c() >= options.target_span_c {
            return Ok(LearnEnd::SpanReached);
        }
        if stalled(&history) {
            return Ok(LearnEnd::Stalled);
        }
        board.rest(options.rest_seconds)?;
    }
    Ok(LearnEnd::RoundLimit)
}

/// Whether the temperature moved less than the stall limit over the last rounds.
fn stalled(history: &[f64]) -> bool {
    let Some(window) = history.len().checked_sub(THERMAL_STALL_ROUNDS).map(|start| &history[start..]) else {
        return false;
    };
    let (low, high) = window.iter().fold((f64::MAX, f64::MIN), |(l, h), t| (l.min(*t), h.max(*t)));
    high - low < THERMAL_STALL_C
}

/// One capture at every orientation; the last capture's temperature.
fn learn_round(
    connection: &mut Connection,
    board: &mut dyn ThermalBoard,
    options: &LearnOptions,
    bins: &mut ThermalBins,
    on_status: OnStatus,
) -> Result<f64, ProcedureError> {
    let mut temp_c = 0.0;
    for (face, force) in options.faces.iter().enumerate() {
        board.place(*force)?;
        let stats = capture_now(connection, options.capture_seconds)?;
        let chip_bins = connection.client.take_temperature_bins()?;
        chip_bins.iter().for_each(|bin| bins.add_chip_bin(face, *force, bin));
        temp_c = f64::from(stats.temp_c);
        let status = LearnStatus { temp_c, span_c: bins.span_c(), bins: bins.len(), chip_bins: chip_bins.len() };
        on_status(status, bins)?;
    }
    Ok(temp_c)
}

/// One capture, after a round trip that makes sure the board's last turn is in force.
pub fn capture_now(connection: &mut Connection, seconds: u8) -> Result<CaptureStats, LinkError> {
    connection.client.calibration(CalibrationSlot::Active)?;
    connection.client.capture(seconds, |_| {}).map(|(stats, _)| stats)
}

pub mod error;
pub mod kept;
pub mod learned;
pub mod resting;
#[cfg(test)]
mod tests;
