//! The chip's own 9-parameter fit: the averaged captures it keeps (wherever they were taken) and the
//! shared `ortho9` solver run on them in f32 on request.
//!
//! NOTE: orientation-free: every still capture is |M (m - o)| = 1 g, whatever the board rested on, so
//! the fit needs no exact placement and a capture that ended between two wanted positions is still
//! good data.

use embedded_hal_async::i2c::I2c;
use embedded_storage_async::nor_flash::NorFlash;
use heapless::Deque;
use shared::calibration::{GyroCalibration, Origin};
use shared::linalg::{self, Vec3};
use shared::ortho9::{self, Ortho9Fit};
use shared::protocol::{CaptureStats, DeviceError, Response, SensorConfig, MAX_KEPT_CAPTURES};
use shared::real::Real;
use shared::Calibration;

use super::Device;

/// What the fit needs of one capture: its means and temperature.
#[derive(Debug, Clone, Copy, PartialEq)]
struct KeptCapture {
    mean_g: Vec3<f32>,
    gyro_mean_dps: Vec3<f32>,
    temp_c: f32,
}

/// The latest [`MAX_KEPT_CAPTURES`] captures, oldest first.
#[derive(Debug, Clone, Default)]
pub(super) struct KeptCaptures {
    captures: Deque<KeptCapture, MAX_KEPT_CAPTURES>,
}

impl KeptCaptures {
    /// Keeps a finished capture, dropping the oldest when full.
    pub(super) fn keep(&mut self, stats: &CaptureStats) {
        if self.captures.is_full() {
            self.captures.pop_front();
        }
        let kept = KeptCapture { mean_g: stats.mean_g, gyro_mean_dps: stats.gyro_mean_dps, temp_c: stats.temp_c };
        let _ = self.captures.push_back(kept);
    }

    /// Forgets every capture.
    pub(super) fn clear(&mut self) {
        self.captures.clear();
    }

    /// The accelerometer means, in g, in a fixed array (the first `len()` are filled).
    fn readings(&self) -> ([Vec3<f32>; MAX_KEPT_CAPTURES], usize) {
        let mut readings = [[0.0f32; 3]; MAX_KEPT_CAPTURES];
        for (reading, kept) in readings.iter_mut().zip(self.captures.iter()) {
            *reading = kept.mean_g;
        }
        (readings, self.captures.len())
    }
}

impl<I, F> Device<I, F>
where
    I: I2c,
    F: NorFlash,
{
    /// Fits `ortho9` to the kept captures and returns it when it is plausible; never made active
    /// (as [`Device::fit_six_position`]: the host activates only what it uploads).
    pub(super) fn fit_ortho9(&mut self) -> Result<Response, DeviceError> {
        let (readings, count) = self.kept.readings();
        let fit = ortho9::fit(&readings[..count]).map_err(DeviceError::Ortho9)?;
        let calibration = ortho9_calibration(&fit, &self.kept, count, self.config);
        calibration.validate().map_err(DeviceError::InvalidCalibration)?;
        let iterations = fit.iterations.min(u32::from(u8::MAX)) as u8;
        Ok(Response::Ortho9Fitted { calibration, captures: count as u8, iterations })
    }
}

/// The calibration record of a fit over `count` captures: gyro bias and temperature averaged over
/// them, and the RMS of |a| - 1 g as the residual.
fn ortho9_calibration(fit: &Ortho9Fit<f32>, kept: &KeptCaptures, count: usize, config: SensorConfig) -> Calibration {
    let share = 1.0 / count as f32;
    let (mut gyro_bias_dps, mut mean_temp_c) = ([0.0f32; 3], 0.0f32);
    for capture in kept.captures.iter() {
        gyro_bias_dps = linalg::add(gyro_bias_dps, linalg::scale(capture.gyro_mean_dps, share));
        mean_temp_c += capture.temp_c * share;
    }
    Calibration {
        origin: Origin::CHIP_ORTHO9,
        range: config.range,
        filter: config.filter,
        matrix: fit.matrix(),
        offset_g: fit.offset(),
        gyro: GyroCalibration { bias_dps: gyro_bias_dps, ..GyroCalibration::default() },
        mean_temp_c,
        temperature: None,
        residual_mg: (fit.cost * share).root() * 1000.0,
    }
}
