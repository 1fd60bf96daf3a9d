//! Register access over an embedded-hal-async I2C bus: the two transactions the chip understands.
//!
//! NOTE: a write is the register address then its new values; a read writes the register address and
//! reads on with a repeated start; bursts auto-increment the address (Product Specification
//! section 9.3), except at FIFO_R_W, which pops the FIFO at every byte (register map section 4.32).

use embedded_hal_async::i2c::I2c;

use super::Error;

/// Writes one register of the chip at `address`.
pub async fn write_register<I: I2c>(bus: &mut I, address: u8, register: u8, value: u8) -> Result<(), Error<I::Error>> {
    bus.write(address, &[register, value]).await.map_err(Error::I2c)
}

/// Writes registers of the chip at `address` one by one, in order: (register, value) pairs.
pub async fn write_each<I: I2c>(bus: &mut I, address: u8, writes: &[(u8, u8)]) -> Result<(), Error<I::Error>> {
    for &(register, value) in writes {
        write_register(bus, address, register, value).await?;
    }
    Ok(())
}

/// Reads `out.len()` bytes starting at `register` of the chip at `address`.
pub async fn read_registers<I: I2c>(
    bus: &mut I,
    address: u8,
    register: u8,
    out: &mut [u8],
) -> Result<(), Error<I::Error>> {
    bus.write_read(address, &[register], out).await.map_err(Error::I2c)
}

/// Reads one register of the chip at `address`.
pub async fn read_register<I: I2c>(bus: &mut I, address: u8, register: u8) -> Result<u8, Error<I::Error>> {
    let mut value = [0u8];
    read_registers(bus, address, register, &mut value).await?;
    Ok(value[0])
}

impl super::Sensor {
    /// Writes `write` to `register` of the sensor when given, then reads the register.
    pub async fn register<I: I2c>(&self, bus: &mut I, register: u8, write: Option<u8>) -> Result<u8, Error<I::Error>> {
        if let Some(value) = write {
            write_register(bus, self.identity.address, register, value).await?;
        }
        read_register(bus, self.identity.address, register).await
    }
}
