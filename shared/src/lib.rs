//! accelcal's shared core: the calibration model, its f32 math and the wire protocol.
//!
//! Everything here is `no_std`, allocation-free and identical on the board and on the host, so the
//! chip and the host compute the same numbers from the same code and speak one protocol.
#![cfg_attr(not(test), no_std)]

pub mod calibration;
pub mod linalg;
pub mod orientation;
pub mod ortho9;
pub mod part;
pub mod protocol;
pub mod real;
pub mod selftest;
pub mod six_position;

pub use calibration::{AccelRange, Calibration, CalibrationError, GyroRange, STANDARD_GRAVITY};
pub use orientation::{Position, PositionError, PositionMap};
pub use six_position::{SixPositionError, SixPositionFit};
