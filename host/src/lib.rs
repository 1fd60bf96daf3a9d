//! accelcal's host library: transports and the protocol client, the simulated board, sessions, the
//! guided calibration, data files, least-squares fits and their reports.
//!
//! The `accelcal` binary only parses arguments and wires these pieces together.

pub mod calibrate;
pub mod client;
pub mod commands;
pub mod connect;
pub mod data;
pub mod error;
pub mod fit;
pub mod port;
pub mod report;
pub mod session;
pub mod sim;
pub mod synthetic;
pub mod ui;
