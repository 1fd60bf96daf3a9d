//! A board's own stream as its sketch prints it: reading its lines, dialects, units and still periods,
//! the status of a live session and what its session keeps are the core's ([`accelcal_core::stream`],
//! re-exported here); this module adds the live reader that keeps a log ([`live`]), reading a saved
//! log's file, and a calibration from a live stream ([`calibrate`]: the port read until the session
//! is done, its session kept on disk ([`session`]), its log fitted, certified and printed).

pub mod calibrate;
mod listen;
pub mod live;
pub mod session;

pub use accelcal_core::stream::*;

/// The text of a saved log, as [`checked_text`] takes it.
pub fn read_text(path: &std::path::Path) -> std::io::Result<String> {
    checked_text(&std::fs::read(path)?)
}
