//! The wire protocol between the board and the host: the one definition of every message.
//!
//! Every request gets exactly one final response; a capture or a stream sends [`Response::Progress`]
//! or [`Response::Sample`] messages before it. Frames are built by [`frame`].

pub mod frame;
mod messages;
pub mod probe;
mod temperature;

pub use frame::{decode, encode, Feed, FrameAccumulator, FrameError};
pub use messages::*;
pub use temperature::{TempBin, TEMP_BINS_PER_MESSAGE};

use crate::calibration::GyroRange;

/// Protocol version carried in every frame's header and in [`Response::Hello`].
///
/// NOTE: 2 from issue 9: the calibration record (origin tag, gyro matrix, temperature model) and the
/// board's serial number in [`DeviceInfo`]. 3 from issue 10: samples carry the sensor's sample time,
/// and the end of a stream says how many samples the board dropped. 4 from issue 16 and issue 12: the
/// chip's own 9-parameter fit (`FitOrtho9`, `Ortho9Fitted`, `DeviceError::Ortho9`), captures that stop when
/// their mean is known well enough ([`Request::CaptureUntil`]) and the chip's temperature bins
/// (`TakeTemperatureBins`); a host of version 3 would read the new messages as garbled frames, so the version
/// names the mismatch instead. 5 from issue 27: the sensor identity carries the register family
/// the chip behaves as (the part is named by its WHO_AM_I, [`crate::part`]). 6 from issue 27: register
/// access ([`Request::Register`], [`Response::Register`]), through which the host runs the datasheet
/// self-test and dumps an unknown part's registers. 7 from issue 27: the board keeps the latest
/// self-test in flash ([`Request::StoreSelfTest`], [`DeviceInfo::self_test`]). 8 from issue 40: the hello
/// moved to the last request, so that no byte of the frame the host writes to a port it does not know
/// yet is one a MicroPython REPL or a bootloader acts on (its index was 0, which COBS made 0x04, and
/// request id 1 was 0x01 0x00).
pub const PROTOCOL_VERSION: u8 = 8;

/// Largest postcard payload of one message, in bytes.
///
/// NOTE: a calibration with its temperature model and filter takes under 240 bytes; twice that leaves the next
/// issues room, and shared's size tests hold every message to half the frame.
pub const MAX_PAYLOAD_LEN: usize = 512;

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

/// Most captures the chip keeps for its 9-parameter fit (the latest ones; older ones are dropped).
///
/// NOTE: the default calibration takes 14 positions and the quick one 10; 16 leaves room for a
/// repeated capture or two, at 28 bytes of RAM each.
pub const MAX_KEPT_CAPTURES: usize = 16;

/// Shortest capture the device accepts, in seconds.
pub const MIN_CAPTURE_SECONDS: u8 = 5;
/// Longest capture the device accepts, in seconds.
pub const MAX_CAPTURE_SECONDS: u8 = 20;
/// Fewest samples a [`Request::CaptureUntil`] averages.
///
/// NOTE: a standard deviation from fewer than about 20 samples is itself uncertain by more than 15 %
/// (1/sqrt(2(n-1))), so a stop rule judged on it would stop early by chance.
pub const MIN_GOAL_SAMPLES: u32 = 20;

/// The range raw gyro samples span: the firmware sets the MPU-6050 to +-1000 deg/s.
///
/// NOTE: +-1000 deg/s, because a hand turning the board between positions reaches several hundred
/// deg/s and a clipped sample corrupts the turn's integral; the 0.03 deg/s step stays below the
/// rate noise at any sample rate the tool uses (0.035 deg/s at 100 Hz).
pub const GYRO_RANGE: GyroRange = GyroRange::Dps1000;
/// Capture length used when the user does not choose one, in seconds.
pub const DEFAULT_CAPTURE_SECONDS: u8 = 10;

/// Largest accelerometer standard deviation of a still board, in g, on any axis: above it a capture
/// is refused as moved.
///
/// NOTE: the noise density of 400 ug/sqrt(Hz) (Product Specification 6.2) gives 2.8 mg rms at the
/// default 100 Hz / 44 Hz filter and 9 mg with the filter off at 1 kHz; 15 mg keeps clear of both
/// while a hand's tremor or a turn of a few degrees exceeds it.
pub const MAX_STILL_ACCEL_STD_G: f32 = 0.015;
/// Largest difference, in g, between |m| of a board at rest and the 1 g of gravity for the reading to
/// count as a position at all (a face on the chip, any wanted orientation on the host).
///
/// NOTE: the sensitivity tolerance of +-3 % and zero-g offsets of +-50 mg (x, y) and +-80 mg (z)
/// (Product Specification 6.2) move |m| at rest by at most about 0.15 g; 0.25 g keeps clear of that
/// while a sensor returning zeros (0 g), a wrong range setting (0.5 g or 2 g) or a board being
/// swung is never taken for a position.
pub const MAX_GRAVITY_ERROR_G: f32 = 0.25;

/// Whether an averaged reading of magnitude `magnitude_g` can be gravity on a board at rest.
pub fn reads_gravity(magnitude_g: f32) -> bool {
    (magnitude_g - 1.0).abs() <= MAX_GRAVITY_ERROR_G
}

/// Largest gyro standard deviation of a still board, in deg/s: the rate noise is 0.05 deg/s rms
/// (Product Specification 6.1), and a turn of a degree a second exceeds 0.5.
pub const MAX_STILL_GYRO_STD_DPS: f32 = 0.5;

#[cfg(test)]
mod tests;
