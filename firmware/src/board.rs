//! What a board crate provides, and the loop that serves the host on it.
//!
//! A board crate sets up its chip (clocks, pins, I2C, flash, the serial port) and hands the pieces to
//! [`serve`]; everything the board does from then on is here, the same on every board: the port is
//! any embedded-io-async byte stream, the LED and the clock are the two small traits below.

use embassy_futures::select::{select, Either};
use embedded_hal::digital::{OutputPin, PinState};
use embedded_hal_async::i2c::I2c;
use embedded_io_async::{Read, Write};
use embedded_storage_async::nor_flash::NorFlash;
use shared::protocol::{SerialNumber, MAX_FRAME_LEN, SERIAL_NUMBER_LEN};

use crate::server::Server;

/// How often the device drains the sensor FIFO, in ms (1 kHz sampling fills 14 bytes/ms of 1024).
pub const POLL_PERIOD_MS: u64 = 10;
/// How long the LED flashes fast after an error, in ms.
pub const ERROR_SHOWN_FOR_MS: u64 = 3000;
/// Bytes read from the port at a time: one USB full-speed packet.
pub const READ_CHUNK_LEN: usize = 64;

/// The board's status LED.
pub trait Led {
    /// Lights the LED, or puts it out.
    fn set_lit(&mut self, lit: bool);
}

/// An LED on a GPIO pin, lit when the pin is high or when it is low (as the Black Pill's PC13).
pub struct LedPin<P> {
    pin: P,
    lit_when_high: bool,
}

impl<P: OutputPin> LedPin<P> {
    /// An LED between the pin and ground: lit when the pin is high.
    pub fn active_high(pin: P) -> Self {
        LedPin { pin, lit_when_high: true }
    }

    /// An LED between the supply and the pin: lit when the pin is low.
    pub fn active_low(pin: P) -> Self {
        LedPin { pin, lit_when_high: false }
    }
}

impl<P: OutputPin> Led for LedPin<P> {
    fn set_lit(&mut self, lit: bool) {
        // NOTE: setting a GPIO level cannot fail on any board here; an LED is not worth a fault.
        let _ = self.pin.set_state(PinState::from(lit == self.lit_when_high));
    }
}

/// The board's time: a millisecond count since boot and a way to wait.
pub trait Clock {
    /// Milliseconds since boot.
    fn now_ms(&self) -> u64;
    /// Waits `ms` milliseconds.
    fn wait_ms(&mut self, ms: u64) -> impl core::future::Future<Output = ()>;
}

/// The serial number from a chip's unique id: its bytes, most significant first, padded with
/// zeros to 12 bytes (a longer id keeps its last 12 bytes, where chips put the varying part).
pub fn serial_number(unique_id: &[u8]) -> SerialNumber {
    let mut serial = [0u8; SERIAL_NUMBER_LEN];
    let taken = unique_id.len().min(SERIAL_NUMBER_LEN);
    serial[SERIAL_NUMBER_LEN - taken..].copy_from_slice(&unique_id[unique_id.len() - taken..]);
    SerialNumber(serial)
}

/// Whether the LED is lit at `now_ms`: a slow heartbeat when idle, steady while capturing or
/// streaming, fast flashing for a few seconds after an error.
pub fn led_lit(now_ms: u64, busy: bool, last_error_ms: Option<u64>) -> bool {
    match last_error_ms {
        Some(at) if now_ms.saturating_sub(at) < ERROR_SHOWN_FOR_MS => now_ms % 200 < 100,
        _ if busy => true,
        _ => now_ms % 1000 < 100,
    }
}

/// Serves the host on `port` for ever.
pub async fn serve<I, F, P, L, C>(server: &mut Server<I, F>, port: &mut P, led: &mut L, clock: &mut C) -> !
where
    I: I2c,
    F: NorFlash,
    P: Read + Write,
    L: Led,
    C: Clock,
{
    let mut last_error_ms = None;
    loop {
        if serve_once(server, port, clock).await {
            last_error_ms = Some(clock.now_ms());
        }
        led.set_lit(led_lit(clock.now_ms(), server.device().is_busy(), last_error_ms));
    }
}

/// One cycle: bytes from the port or a poll period passed, then every response written. Whether
/// one of them carried an error.
pub async fn serve_once<I, F, P, C>(server: &mut Server<I, F>, port: &mut P, clock: &mut C) -> bool
where
    I: I2c,
    F: NorFlash,
    P: Read + Write,
    C: Clock,
{
    let mut chunk = [0u8; READ_CHUNK_LEN];
    match select(port.read(&mut chunk), clock.wait_ms(POLL_PERIOD_MS)).await {
        Either::First(Ok(n)) => server.receive(&chunk[..n]).await,
        Either::First(Err(_)) => clock.wait_ms(POLL_PERIOD_MS).await, // no host on the port yet
        Either::Second(()) => server.poll().await,
    }
    let mut any_error = false;
    let mut buffer = [0u8; MAX_FRAME_LEN];
    while let Some((frame, is_error)) = server.next_frame(&mut buffer) {
        any_error |= is_error;
        // NOTE: a host gone mid-frame loses this response; the device carries on.
        if port.write_all(frame).await.is_ok() {
            let _ = port.flush().await;
        }
    }
    any_error
}

/// The clock of every board here: embassy-time, driven by the board's HAL.
#[cfg(feature = "embassy-time")]
pub struct EmbassyClock;

#[cfg(feature = "embassy-time")]
impl Clock for EmbassyClock {
    fn now_ms(&self) -> u64 {
        embassy_time::Instant::now().as_millis()
    }

    async fn wait_ms(&mut self, ms: u64) {
        embassy_time::Timer::after_millis(ms).await;
    }
}

#[cfg(test)]
mod tests;
