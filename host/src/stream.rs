//! A board's own stream as its sketch prints it: reading its lines, dialects, units and still periods
//! are the core's ([`accelcal_core::stream`], re-exported here); this module adds the live reader
//! that keeps a log and reading a saved log's file.

pub mod live;

pub use accelcal_core::stream::*;

/// The text of a saved log, as [`checked_text`] takes it.
pub fn read_text(path: &std::path::Path) -> std::io::Result<String> {
    checked_text(&std::fs::read(path)?)
}
