//! The measurements: one sample of the data registers or the FIFO, as signed 16-bit counts.

use embedded_hal_async::i2c::I2c;

use super::access::read_registers;
use super::registers as reg;
use super::{Error, Sensor};

/// One sample as the sensor delivers it: signed 16-bit counts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct RawSample {
    /// Accelerometer x, y, z in LSB.
    pub accel: [i16; 3],
    /// Temperature in LSB of the MPU-6050's encoding (raw / 340 + 36.53), whatever the part.
    pub temp: i16,
    /// Gyro x, y, z in LSB.
    pub gyro: [i16; 3],
}

impl RawSample {
    /// Parses the 14 bytes of a FIFO sample or of the data registers (big-endian, register order).
    pub fn from_be_bytes(bytes: &[u8; reg::FIFO_SAMPLE_LEN]) -> Self {
        let word = |i: usize| i16::from_be_bytes([bytes[2 * i], bytes[2 * i + 1]]);
        RawSample { accel: [word(0), word(1), word(2)], temp: word(3), gyro: [word(4), word(5), word(6)] }
    }

    /// As [`RawSample::from_be_bytes`], from a slice of at least 14 bytes (the rest is ignored).
    pub(super) fn from_be_slice(bytes: &[u8]) -> Self {
        let mut one = [0u8; reg::FIFO_SAMPLE_LEN];
        one.copy_from_slice(&bytes[..reg::FIFO_SAMPLE_LEN]);
        RawSample::from_be_bytes(&one)
    }

    /// Temperature in degC.
    pub fn temp_c(&self) -> f32 {
        reg::temp_c(f32::from(self.temp))
    }
}

impl Sensor {
    /// Reads the latest sample from the data registers (no FIFO).
    pub async fn read_latest<I: I2c>(&mut self, bus: &mut I) -> Result<RawSample, Error<I::Error>> {
        let mut bytes = [0u8; reg::FIFO_SAMPLE_LEN];
        read_registers(bus, self.identity.address, reg::ACCEL_XOUT_H, &mut bytes).await?;
        Ok(self.decoded(&bytes))
    }

    /// A sample's 14 bytes (or more) as a sample, its temperature in the MPU-6050's encoding.
    pub(super) fn decoded(&self, bytes: &[u8]) -> RawSample {
        let sample = RawSample::from_be_slice(bytes);
        RawSample { temp: self.temperature.apply(sample.temp), ..sample }
    }
}
