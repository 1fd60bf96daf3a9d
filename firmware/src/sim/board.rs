//! The simulated board around the sensor: its serial number and its flash.

use shared::protocol::{SerialNumber, SERIAL_NUMBER_LEN};

/// The simulated board's serial number: "SIM" and a zero, then the seed, so that two simulated boards
/// differ as real ones do and a simulated serial is never mistaken for an STM32's unique ID.
pub fn sim_serial_number(seed: u64) -> SerialNumber {
    let mut id = [0u8; SERIAL_NUMBER_LEN];
    id[..3].copy_from_slice(b"SIM");
    id[4..].copy_from_slice(&seed.to_be_bytes());
    SerialNumber(id)
}

/// The simulated board's flash: four 4 KiB pages (small pages exercise page changes quickly).
pub type SimFlash = super::flash::RamFlash<4096, 4>;
/// The byte range of [`SimFlash`] holding the calibration: all of it.
pub const SIM_FLASH_RANGE: core::ops::Range<u32> = 0..4 * 4096;
