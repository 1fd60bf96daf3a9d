//! accelcal on an ESP32-C3 board: pins, flash partition and the USB-Serial-JTAG port, handed to the
//! firmware library, which does everything else.
//!
//! The setup is in `esp.rs`, built for the board only: on the host this crate is an empty program,
//! so `cargo test --workspace` needs no target toolchain.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(target_os = "none")]
mod esp;

#[cfg(not(target_os = "none"))]
fn main() {}
