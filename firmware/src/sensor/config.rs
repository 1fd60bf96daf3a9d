//! Configuration: power, full-scale ranges, the digital low-pass filter and the sample rate.

use embedded_hal_async::i2c::I2c;
use shared::part::Family;
use shared::protocol::{LowPassFilter, SensorConfig, GYRO_RANGE};
use shared::AccelRange;

use super::access::write_each;
use super::registers as reg;
use super::{Error, Sensor};

impl Sensor {
    /// Wakes the chip and applies range, filter and sample rate; returns the configuration achieved.
    pub async fn configure<I: I2c>(
        &mut self,
        bus: &mut I,
        config: SensorConfig,
    ) -> Result<SensorConfig, Error<I::Error>> {
        let divider = sample_rate_divider(config.sample_rate_hz)?;
        let writes = [
            (reg::PWR_MGMT_1, reg::PWR_MGMT_1_AWAKE_PLL_X),
            (reg::ACCEL_CONFIG, afs_sel(config.range) << reg::FULL_SCALE_SHIFT),
            (reg::GYRO_CONFIG, GYRO_RANGE.fs_sel() << reg::FULL_SCALE_SHIFT),
            (reg::CONFIG, dlpf_cfg(config.filter)),
            (reg::SMPLRT_DIV, divider),
            (reg::INT_ENABLE, reg::FIFO_OFLOW),
            // NOTE: the MPU-6500 family's accelerometer has its own filter: CONFIG filters its gyro
            // only (RM-MPU-6500A 4.6, 4.8). A_DLPF_CFG 0-6 (460, 184, 92, 41, 20, 10, 5 Hz) are the
            // nearest to DLPF_CFG 0-6 (260, 184, 94, 44, 21, 10, 5 Hz), so the same value serves.
            (reg::ACCEL_CONFIG2, dlpf_cfg(config.filter)),
        ];
        let count = if self.identity.family == Family::Mpu6500 { writes.len() } else { writes.len() - 1 };
        write_each(bus, self.identity.address, &writes[..count]).await?;
        let achieved = (reg::GYRO_OUTPUT_RATE_HZ / (1 + u32::from(divider))) as u16;
        self.config = SensorConfig { sample_rate_hz: achieved, ..config };
        Ok(self.config)
    }
}

/// SMPLRT_DIV for a sample rate: 1 kHz / (1 + divider) must equal the rate exactly.
fn sample_rate_divider<E>(rate_hz: u16) -> Result<u8, Error<E>> {
    let invalid = Error::InvalidRate { rate_hz };
    if rate_hz == 0 || !reg::GYRO_OUTPUT_RATE_HZ.is_multiple_of(u32::from(rate_hz)) {
        return Err(invalid);
    }
    u8::try_from(reg::GYRO_OUTPUT_RATE_HZ / u32::from(rate_hz) - 1).map_err(|_| invalid)
}

/// ACCEL_CONFIG's AFS_SEL for a range: 0-3 for +-2, 4, 8, 16 g (register map section 4.5).
fn afs_sel(range: AccelRange) -> u8 {
    match range {
        AccelRange::G2 => 0,
        AccelRange::G4 => 1,
        AccelRange::G8 => 2,
        AccelRange::G16 => 3,
    }
}

/// DLPF_CFG for a filter (register map section 4.3, table).
fn dlpf_cfg(filter: LowPassFilter) -> u8 {
    match filter {
        LowPassFilter::Hz260 => 0,
        LowPassFilter::Hz184 => 1,
        LowPassFilter::Hz94 => 2,
        LowPassFilter::Hz44 => 3,
        LowPassFilter::Hz21 => 4,
        LowPassFilter::Hz10 => 5,
        LowPassFilter::Hz5 => 6,
    }
}
