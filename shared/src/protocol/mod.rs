//! The wire protocol between the board and the host: the one definition of every message.
//!
//! Every request gets exactly one final response; a capture or a stream sends [`Response::Progress`]
//! or [`Response::Sample`] messages before it. Frames are built by [`frame`].

pub mod frame;
mod messages;

pub use frame::{decode, encode, Feed, FrameAccumulator, FrameError};
pub use messages::*;

/// Protocol version carried in every frame's header and in [`Response::Hello`].
pub const PROTOCOL_VERSION: u8 = 1;

/// Largest postcard payload of one message, in bytes.
pub const MAX_PAYLOAD_LEN: usize = 200;

/// Largest encoded frame, delimiter included: COBS of version + request id + payload + CRC, plus 0x00.
pub const MAX_FRAME_LEN: usize = cobs::max_encoding_length(frame::HEADER_LEN + MAX_PAYLOAD_LEN + frame::CRC_LEN) + 1;

/// USB vendor id of the board's CDC-ACM serial port (pid.codes open-source vendor id).
pub const USB_VID: u16 = 0x1209;
/// USB product id of the board's CDC-ACM serial port (pid.codes test id until one is allocated).
pub const USB_PID: u16 = 0x0001;
/// USB manufacturer string.
pub const USB_MANUFACTURER: &str = "accelcal";
/// USB product string; the host recognises the board by it together with the ids.
pub const USB_PRODUCT: &str = "accelcal MPU-6050 calibrator";

/// Shortest capture the device accepts, in seconds.
pub const MIN_CAPTURE_SECONDS: u8 = 5;
/// Longest capture the device accepts, in seconds.
pub const MAX_CAPTURE_SECONDS: u8 = 20;
/// Capture length used when the user does not choose one, in seconds.
pub const DEFAULT_CAPTURE_SECONDS: u8 = 10;

#[cfg(test)]
mod tests;
