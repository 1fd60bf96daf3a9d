//! accelcal's host library: data files, least-squares fits and their reports.
//!
//! The `accelcal` binary only parses arguments and wires these pieces together.

pub mod data;
pub mod fit;
pub mod report;
pub mod synthetic;
