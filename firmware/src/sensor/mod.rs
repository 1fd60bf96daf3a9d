//! The MPU-6050 driver: the project's own register code over an embedded-hal-async I2C bus.
//!
//! One file per feature area, all on [`access`]'s two transactions: [`identify`] (which chip, where),
//! [`family`] (which register family it behaves as, and what differs between them),
//! [`config`] (power, ranges, filter, rate), [`fifo`] (start, stop, read whole samples), [`data`]
//! (one sample). [`registers`] is the one home of the datasheet's addresses and bits. The bus stays
//! with the caller, so that the device can probe both addresses and find a chip that came back.

pub mod access;
mod config;
mod data;
mod family;
mod fifo;
mod identify;
pub mod registers;

use shared::protocol::{DeviceError, SensorConfig, SensorIdentity};

pub use data::RawSample;

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

/// A found and configured MPU-6050 (or compatible part); the bus stays with the caller.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sensor {
    identity: SensorIdentity,
    config: SensorConfig,
    /// How its TEMP_OUT becomes the MPU-6050's encoding, which the driver hands samples on in.
    temperature: family::TempEncoding,
}

impl Sensor {
    /// Which chip answered and where.
    pub fn identity(&self) -> SensorIdentity {
        self.identity
    }

    /// The configuration last applied.
    pub fn config(&self) -> SensorConfig {
        self.config
    }
}

#[cfg(test)]
mod tests;
