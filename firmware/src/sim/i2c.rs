//! The simulated chip's side of the I2C bus, behind embedded-hal 1.0's blocking and async traits, so
//! that the driver runs on it exactly as on a board's bus.

use embedded_hal::i2c::{ErrorKind, ErrorType, NoAcknowledgeSource, Operation};

use super::SimMpu6050;
use crate::sensor::registers as reg;

/// Why a simulated transaction failed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BusFault {
    /// Nothing acknowledged the address (wrong address, or the sensor is disconnected).
    NoAcknowledge,
    /// A fault injected by a test.
    Injected,
}

impl embedded_hal::i2c::Error for BusFault {
    fn kind(&self) -> ErrorKind {
        match self {
            BusFault::NoAcknowledge => ErrorKind::NoAcknowledge(NoAcknowledgeSource::Address),
            BusFault::Injected => ErrorKind::Other,
        }
    }
}

impl ErrorType for SimMpu6050 {
    type Error = BusFault;
}

/// The chip's side of I2C transactions: a write sets the register pointer (its first byte) and
/// writes on from there; a read reads on from the pointer.
impl embedded_hal::i2c::I2c for SimMpu6050 {
    fn transaction(&mut self, address: u8, operations: &mut [Operation<'_>]) -> Result<(), BusFault> {
        self.acknowledge(address)?;
        let mut pointer = 0u8;
        for operation in operations {
            match operation {
                Operation::Write(bytes) => pointer = self.write_from(bytes, pointer),
                Operation::Read(buffer) => pointer = self.read_into(buffer, pointer),
            }
        }
        Ok(())
    }
}

/// The same chip on an async bus: the simulation never waits, so each operation completes at once.
impl embedded_hal_async::i2c::I2c for SimMpu6050 {
    async fn transaction(&mut self, address: u8, operations: &mut [Operation<'_>]) -> Result<(), BusFault> {
        embedded_hal::i2c::I2c::transaction(self, address, operations)
    }
}

impl SimMpu6050 {
    /// A written burst: the register address, then values for it and the registers after it.
    fn write_from(&mut self, bytes: &[u8], pointer: u8) -> u8 {
        let Some((&first, data)) = bytes.split_first() else {
            return pointer;
        };
        for (offset, &value) in data.iter().enumerate() {
            self.write_register(first.wrapping_add(offset as u8), value);
        }
        first.wrapping_add(data.len() as u8)
    }

    /// A read burst from `pointer`.
    fn read_into(&mut self, buffer: &mut [u8], pointer: u8) -> u8 {
        let mut address = pointer;
        for byte in buffer.iter_mut() {
            *byte = self.read_register(address);
            // NOTE: burst reads auto-increment the register address, except on FIFO_R_W, which
            // pops the FIFO at every byte (register map 4.32).
            if address != reg::FIFO_R_W {
                address = address.wrapping_add(1);
            }
        }
        address
    }
}

/// The chip's side of a bus that arrives one event at a time (an emulated I2C controller's start,
/// address, byte and stop, host `sim::emulated`): the register pointer carries over between
/// transactions, as on the chip, so that a write of the register address and a repeated-start read
/// from it meet as they do in [`embedded_hal::i2c::I2c::transaction`].
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
pub struct BytewiseTarget {
    pointer: u8,
    /// Whether the next written byte is a register address (the first of a write).
    expects_address: bool,
}

impl BytewiseTarget {
    /// The controller addresses `address`: whether the chip acknowledges.
    pub fn address(&mut self, chip: &mut SimMpu6050, address: u8) -> bool {
        self.expects_address = true;
        chip.acknowledge(address).is_ok()
    }

    /// The controller writes `value`: a register address first, then values from it on.
    pub fn write(&mut self, chip: &mut SimMpu6050, value: u8) {
        if core::mem::take(&mut self.expects_address) {
            self.pointer = value;
        } else {
            self.pointer = chip.write_from(&[self.pointer, value], self.pointer);
        }
    }

    /// The controller reads a byte.
    pub fn read(&mut self, chip: &mut SimMpu6050) -> u8 {
        let mut byte = [0];
        self.pointer = chip.read_into(&mut byte, self.pointer);
        byte[0]
    }
}
