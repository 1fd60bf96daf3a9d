//! Lends the I2C bus to the `mpu6050` crate for one operation at a time.
//!
//! NOTE: `mpu6050::Mpu6050` takes its bus by value and has no way to give it back, and embedded-hal
//! 0.2 has no blanket impl for `&mut I2C`; this borrow lets the driver keep its bus, probe both
//! addresses and run register access the crate does not offer.

use embedded_hal::blocking::i2c::{Write, WriteRead};

/// A borrowed I2C bus that implements the embedded-hal 0.2 traits the `mpu6050` crate needs.
pub struct Borrowed<'a, I>(pub &'a mut I);

impl<I: Write> Write for Borrowed<'_, I> {
    type Error = I::Error;

    fn write(&mut self, address: u8, bytes: &[u8]) -> Result<(), Self::Error> {
        self.0.write(address, bytes)
    }
}

impl<I: WriteRead> WriteRead for Borrowed<'_, I> {
    type Error = I::Error;

    fn write_read(&mut self, address: u8, bytes: &[u8], buffer: &mut [u8]) -> Result<(), Self::Error> {
        self.0.write_read(address, bytes, buffer)
    }
}
