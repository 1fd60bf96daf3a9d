//! The FIFO: started empty with every measurement in it, stopped, and read in whole samples.

use embedded_hal_async::i2c::I2c;

use super::access::{read_register, read_registers, write_each};
use super::registers as reg;
use super::{Error, RawSample, Sensor};

/// Samples read from the FIFO in one I2C transaction (bounded so a read never stalls the bus long).
const SAMPLES_PER_READ: usize = 8;

impl Sensor {
    /// Empties the FIFO, clears a pending overflow and starts filling it with every sample.
    pub async fn start_fifo<I: I2c>(&mut self, bus: &mut I) -> Result<(), Error<I::Error>> {
        self.stop_fifo_resetting(bus, reg::USER_CTRL_FIFO_RESET).await?;
        read_register(bus, self.identity.address, reg::INT_STATUS).await?; // clears a stale overflow
        let start = [(reg::FIFO_EN, reg::FIFO_EN_TEMP_GYRO_ACCEL), (reg::USER_CTRL, reg::USER_CTRL_FIFO_EN)];
        write_each(bus, self.identity.address, &start).await
    }

    /// Stops filling the FIFO.
    pub async fn stop_fifo<I: I2c>(&mut self, bus: &mut I) -> Result<(), Error<I::Error>> {
        self.stop_fifo_resetting(bus, 0).await
    }

    /// Stops filling the FIFO, then writes USER_CTRL: 0, or FIFO_RESET to empty it as well.
    async fn stop_fifo_resetting<I: I2c>(&mut self, bus: &mut I, user_ctrl: u8) -> Result<(), Error<I::Error>> {
        write_each(bus, self.identity.address, &[(reg::FIFO_EN, 0), (reg::USER_CTRL, user_ctrl)]).await
    }

    /// Pops whole samples from the FIFO into `out`; returns how many. An overflow is an error.
    pub async fn read_fifo<I: I2c>(&mut self, bus: &mut I, out: &mut [RawSample]) -> Result<usize, Error<I::Error>> {
        let address = self.identity.address;
        if read_register(bus, address, reg::INT_STATUS).await? & reg::FIFO_OFLOW != 0 {
            return Err(Error::FifoOverflow);
        }
        let mut count = [0u8; 2];
        read_registers(bus, address, reg::FIFO_COUNT_H, &mut count).await?;
        let available = usize::from(u16::from_be_bytes(count)) / reg::FIFO_SAMPLE_LEN;
        let wanted = available.min(out.len());
        let mut bytes = [0u8; reg::FIFO_SAMPLE_LEN * SAMPLES_PER_READ];
        for chunk in out[..wanted].chunks_mut(SAMPLES_PER_READ) {
            let len = chunk.len() * reg::FIFO_SAMPLE_LEN;
            read_registers(bus, address, reg::FIFO_R_W, &mut bytes[..len]).await?;
            for (sample, raw) in chunk.iter_mut().zip(bytes.chunks_exact(reg::FIFO_SAMPLE_LEN)) {
                *sample = self.decoded(raw);
            }
        }
        Ok(wanted)
    }
}
