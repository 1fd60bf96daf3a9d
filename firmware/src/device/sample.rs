//! The one place a sensor reading becomes a wire message.

use shared::protocol::{Sample, SensorConfig};
use shared::Calibration;

use crate::sensor::registers::GYRO_LSB_PER_DPS;
use crate::sensor::RawSample;

/// Counts to g, deg/s and degC, corrected with the calibration at the sample's own temperature when
/// one is given; `index` is its sequence number, `time_us` the sensor's sample time.
pub fn sample_message(
    raw: &RawSample,
    index: u32,
    time_us: u64,
    config: SensorConfig,
    calibration: Option<&Calibration>,
) -> Sample {
    let lsb = config.range.lsb_per_g();
    let accel_g = raw.accel.map(|a| f32::from(a) / lsb);
    let gyro_dps = raw.gyro.map(|g| f32::from(g) / GYRO_LSB_PER_DPS);
    let temp_c = raw.temp_c();
    let (accel_g, gyro_dps) = match calibration {
        Some(c) => (c.apply_at(accel_g, temp_c), c.apply_gyro(gyro_dps, temp_c)),
        None => (accel_g, gyro_dps),
    };
    Sample { index, time_us, accel_g, gyro_dps, temp_c }
}
