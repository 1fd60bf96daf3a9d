//! The MPU-6050 driver layer: identification, configuration, FIFO reads.
//!
//! Sensor access goes through the `mpu6050` crate (embedded-hal 0.2 blocking I2C); what it lacks
//! (FIFO, sample-rate divider, filter, interrupt status) goes through its register access.

mod bus;
mod family;
pub mod registers;

use embedded_hal::blocking::i2c::{Write, WriteRead};
use mpu6050::device::{AccelRange as ChipRange, GyroRange};
use mpu6050::{Mpu6050, Mpu6050Error};
use shared::part::{Family, TemperatureFormula};
use shared::protocol::{DeviceError, LowPassFilter, SensorConfig, SensorIdentity};
use shared::AccelRange;

use bus::Borrowed;
use registers as reg;

/// What went wrong talking to the sensor.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Error<E> {
    /// The I2C transaction failed.
    I2c(E),
    /// Nothing acknowledges at 0x68 or 0x69.
    Missing,
    /// A chip answers, but its WHO_AM_I is neither an MPU-6050 nor a known compatible part.
    UnknownChip { address: u8, who_am_i: u8 },
    /// The sample rate cannot be made from the 1 kHz gyro output rate (4-1000 Hz).
    InvalidRate { rate_hz: u16 },
    /// The FIFO overflowed: samples were lost and the byte stream may be misaligned.
    FifoOverflow,
}

impl<E> From<Mpu6050Error<E>> for Error<E> {
    fn from(error: Mpu6050Error<E>) -> Self {
        match error {
            Mpu6050Error::I2c(e) => Error::I2c(e),
            // NOTE: only the crate's `init` checks the chip id, and this driver does not call it.
            Mpu6050Error::InvalidChipId(who_am_i) => Error::UnknownChip { address: 0, who_am_i },
        }
    }
}

impl<E> Error<E> {
    /// The protocol error the host is told.
    pub fn to_device_error(&self) -> DeviceError {
        match *self {
            Error::I2c(_) => DeviceError::Bus,
            Error::Missing => DeviceError::SensorMissing,
            Error::UnknownChip { address, who_am_i } => DeviceError::UnknownSensor { address, who_am_i },
            Error::InvalidRate { rate_hz } => DeviceError::InvalidRate { rate_hz },
            Error::FifoOverflow => DeviceError::FifoOverflow,
        }
    }
}

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

    /// Temperature in degC.
    pub fn temp_c(&self) -> f32 {
        f32::from(self.temp) / reg::TEMP_LSB_PER_C + reg::TEMP_OFFSET_C
    }
}

/// Samples read from the FIFO in one I2C transaction (bounded so a read never stalls the bus long).
const SAMPLES_PER_READ: usize = 8;

/// A found and configured MPU-6050 (or compatible part); the bus stays with the caller.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sensor {
    identity: SensorIdentity,
    config: SensorConfig,
}

impl Sensor {
    /// Looks for the chip at 0x68, then 0x69, by WHO_AM_I.
    pub fn probe<I, E>(bus: &mut I) -> Result<Self, Error<E>>
    where
        I: Write<Error = E> + WriteRead<Error = E>,
    {
        for address in reg::ADDRESSES {
            let Ok(who_am_i) = Mpu6050::new_with_addr(Borrowed(bus), address).read_byte(reg::WHO_AM_I) else {
                continue;
            };
            let Some(family) = family::family_of(bus, address, who_am_i)? else {
                return Err(Error::UnknownChip { address, who_am_i });
            };
            let identity = SensorIdentity { address, who_am_i, family };
            return Ok(Sensor { identity, config: SensorConfig::default() });
        }
        Err(Error::Missing)
    }

    /// Which chip answered and where.
    pub fn identity(&self) -> SensorIdentity {
        self.identity
    }

    /// The configuration last applied.
    pub fn config(&self) -> SensorConfig {
        self.config
    }

    /// How this part's TEMP_OUT reads (the driver hands samples on in the MPU-6050's encoding).
    fn temperature(&self) -> TemperatureFormula {
        self.identity.identification().temperature()
    }

    fn chip<'a, I, E>(&self, bus: &'a mut I) -> Mpu6050<Borrowed<'a, I>>
    where
        I: Write<Error = E> + WriteRead<Error = E>,
    {
        Mpu6050::new_with_addr(Borrowed(bus), self.identity.address)
    }

    /// Wakes the chip and applies range, filter and sample rate; returns the configuration achieved.
    pub fn configure<I, E>(&mut self, bus: &mut I, config: SensorConfig) -> Result<SensorConfig, Error<E>>
    where
        I: Write<Error = E> + WriteRead<Error = E>,
    {
        let divider = sample_rate_divider(config.sample_rate_hz)?;
        let mut chip = self.chip(bus);
        chip.write_byte(reg::PWR_MGMT_1, reg::PWR_MGMT_1_AWAKE_PLL_X)?;
        chip.set_accel_range(chip_range(config.range))?;
        chip.set_gyro_range(GyroRange::D1000)?;
        chip.write_byte(reg::CONFIG, filter_setting(config.filter))?;
        if self.identity.family == Family::Mpu6500 {
            // NOTE: on the MPU-6500 family CONFIG filters the gyro only (RM-MPU-6500A 4.6).
            chip.write_byte(reg::ACCEL_CONFIG2, family::accel_config2(config.filter))?;
        }
        chip.write_byte(reg::SMPLRT_DIV, divider)?;
        chip.write_byte(reg::INT_ENABLE, reg::FIFO_OFLOW)?;
        let achieved = (reg::GYRO_OUTPUT_RATE_HZ / (1 + u32::from(divider))) as u16;
        self.config = SensorConfig { sample_rate_hz: achieved, ..config };
        Ok(self.config)
    }

    /// Empties the FIFO, clears a pending overflow and starts filling it with every sample.
    pub fn start_fifo<I, E>(&mut self, bus: &mut I) -> Result<(), Error<E>>
    where
        I: Write<Error = E> + WriteRead<Error = E>,
    {
        let mut chip = self.chip(bus);
        chip.write_byte(reg::FIFO_EN, 0)?;
        chip.write_byte(reg::USER_CTRL, reg::USER_CTRL_FIFO_RESET)?;
        chip.read_byte(reg::INT_STATUS)?; // clears a stale overflow flag
        chip.write_byte(reg::FIFO_EN, reg::FIFO_EN_TEMP_GYRO_ACCEL)?;
        chip.write_byte(reg::USER_CTRL, reg::USER_CTRL_FIFO_EN)?;
        Ok(())
    }

    /// Stops filling the FIFO.
    pub fn stop_fifo<I, E>(&mut self, bus: &mut I) -> Result<(), Error<E>>
    where
        I: Write<Error = E> + WriteRead<Error = E>,
    {
        let mut chip = self.chip(bus);
        chip.write_byte(reg::FIFO_EN, 0)?;
        chip.write_byte(reg::USER_CTRL, 0)?;
        Ok(())
    }

    /// Pops whole samples from the FIFO into `out`; returns how many. An overflow is an error.
    pub fn read_fifo<I, E>(&mut self, bus: &mut I, out: &mut [RawSample]) -> Result<usize, Error<E>>
    where
        I: Write<Error = E> + WriteRead<Error = E>,
    {
        let mut chip = self.chip(bus);
        if chip.read_byte(reg::INT_STATUS)? & reg::FIFO_OFLOW != 0 {
            return Err(Error::FifoOverflow);
        }
        let mut count = [0u8; 2];
        chip.read_bytes(reg::FIFO_COUNT_H, &mut count)?;
        let available = usize::from(u16::from_be_bytes(count)) / reg::FIFO_SAMPLE_LEN;
        let wanted = available.min(out.len());
        let mut bytes = [0u8; reg::FIFO_SAMPLE_LEN * SAMPLES_PER_READ];
        for chunk in out[..wanted].chunks_mut(SAMPLES_PER_READ) {
            let len = chunk.len() * reg::FIFO_SAMPLE_LEN;
            chip.read_bytes(reg::FIFO_R_W, &mut bytes[..len])?;
            for (sample, raw) in chunk.iter_mut().zip(bytes.chunks_exact(reg::FIFO_SAMPLE_LEN)) {
                let mut one = [0u8; reg::FIFO_SAMPLE_LEN];
                one.copy_from_slice(raw);
                *sample = self.decoded(&one);
            }
        }
        Ok(wanted)
    }

    /// Reads the latest sample from the data registers (no FIFO).
    pub fn read_latest<I, E>(&mut self, bus: &mut I) -> Result<RawSample, Error<E>>
    where
        I: Write<Error = E> + WriteRead<Error = E>,
    {
        let mut bytes = [0u8; reg::FIFO_SAMPLE_LEN];
        self.chip(bus).read_bytes(reg::ACCEL_XOUT_H, &mut bytes)?;
        Ok(self.decoded(&bytes))
    }

    /// A sample's bytes as a sample, its temperature in the MPU-6050's encoding.
    fn decoded(&self, bytes: &[u8; reg::FIFO_SAMPLE_LEN]) -> RawSample {
        let sample = RawSample::from_be_bytes(bytes);
        RawSample { temp: family::in_mpu6050_encoding(self.temperature(), sample.temp), ..sample }
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

fn chip_range(range: AccelRange) -> ChipRange {
    match range {
        AccelRange::G2 => ChipRange::G2,
        AccelRange::G4 => ChipRange::G4,
        AccelRange::G8 => ChipRange::G8,
        AccelRange::G16 => ChipRange::G16,
    }
}

/// DLPF_CFG for a filter (register map section 4.3, table).
fn filter_setting(filter: LowPassFilter) -> u8 {
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

#[cfg(test)]
mod tests;
