//! accelcal on the WeAct Black Pill (STM32F411CE or STM32F401CE): clocks, pins, flash and USB,
//! handed to the firmware library, which does everything else.
//!
//! The setup is in `stm32.rs`, built for the board only: on the host this crate is an empty program,
//! so `cargo test --workspace` needs no target toolchain.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(target_os = "none")]
mod stm32;

#[cfg(not(target_os = "none"))]
fn main() {}
