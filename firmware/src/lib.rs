//! accelcal's firmware library: everything the board does, target-independent and tested on the host.
//!
//! The board crates (`boards/`) only set up their chip and hand its pieces to [`board::serve`].
#![cfg_attr(not(test), no_std)]

pub mod board;
pub mod capture;
pub mod device;
pub mod link;
pub mod sensor;
pub mod server;
#[cfg(feature = "sim")]
pub mod sim;
pub mod storage;
pub mod temperature_bins;
#[cfg(feature = "usb")]
pub mod usb;
