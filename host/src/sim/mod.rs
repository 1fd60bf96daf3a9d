//! The host side of the simulation: the firmware library's own `Device` on the simulated MPU-6050
//! and a RAM flash, served over any [`Port`] from a thread, exactly as the real board serves its USB
//! port; a pseudo-terminal server for `accelcal sim --pty`; random draws and synthetic data sets;
//! `accelcal thermal --sim`'s story ([`thermal`]).
//!
//! Whoever turns the simulated board (the procedure's simulated hand, a test) does so through the
//! [`SimCommand`] handle that [`SimBoard::controls`] gives.

mod board;
mod clock;
mod commands;
mod emulated;
mod fixture;
pub mod noise;
mod outgoing;
mod parts;
mod pty;
pub mod replay;
mod serve;
pub mod thermal;
mod truth;

pub use accelcal_core::sim::{
    person, random, sessions, sketch, synthetic, turn, SimCommand, SimulatedHand, SimulatedSession,
};

pub use board::{PowerOn, SensorChoice, SimBoard, SimSensor};
pub use clock::Pace;
pub use emulated::{serve_emulated, EmulatorError};
pub use fixture::{Pull, SimulatedMember};
pub use parts::{FaultyAxis, SimPartChoice};
pub use pty::{serve_pty, SimError};

use crate::link::Port;
