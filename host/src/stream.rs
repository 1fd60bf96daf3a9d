//! A board's own stream as its sketch prints it: reading its lines, dialects, units and still periods,
//! the status of a live session and what its session keeps are the core's ([`accelcal_core::stream`],
//! re-exported here), and so is the live session's run (`accelcal_core::run::stream`: listened to
//! until done, its log fitted, what to print); this module adds the port read with the clock and
//! Ctrl-C into a log ([`live`]), reading a saved log's file, the session kept on disk ([`session`]),
//! the wiring of a calibration from a live stream ([`calibrate`], which certifies when the run
//! says it may), and a saved log read as a still recording for `accelcal noise` ([`noise_input`]).

pub mod calibrate;
pub mod live;
pub mod noise_input;
pub mod session;

pub use accelcal_core::stream::*;

/// The text of a saved log, as [`checked_text`] takes it.
pub fn read_text(path: &std::path::Path) -> std::io::Result<String> {
    checked_text(&std::fs::read(path)?)
}
