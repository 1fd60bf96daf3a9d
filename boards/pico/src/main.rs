//! accelcal on the Raspberry Pi Pico (RP2040) or Pico 2 (RP2350): pins, flash and USB, handed to the
//! firmware library, which does everything else.
//!
//! The setup is in `rp.rs`, built for the board only: on the host this crate is an empty program,
//! so `cargo test --workspace` needs no target toolchain.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(target_os = "none")]
mod rp;

#[cfg(not(target_os = "none"))]
fn main() {}
