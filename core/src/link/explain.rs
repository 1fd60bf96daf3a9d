//! What the device's typed errors mean for the user: one line each, the cause and what to do.
//! Numbers come from the constants that set them, never restated.

use shared::ortho9::{Ortho9Error, MIN_READINGS};
use shared::protocol::{DeviceError, FrameError, MAX_CAPTURE_SECONDS, MIN_CAPTURE_SECONDS, PROTOCOL_VERSION};
use shared::SixPositionError;

use crate::calibration::calibration_reason;

/// One line: what the device said went wrong, and what to do.
pub fn explain(error: &DeviceError) -> String {
    match *error {
        DeviceError::SensorMissing
        | DeviceError::UnknownSensor { .. }
        | DeviceError::Bus
        | DeviceError::FifoOverflow => sensor(error),
        DeviceError::Moved { .. }
        | DeviceError::Clipped { .. }
        | DeviceError::Cancelled
        | DeviceError::InvalidDuration { .. }
        | DeviceError::InvalidRate { .. } => capture(error),
        DeviceError::SixPosition(reason) => six_position(reason),
        DeviceError::Ortho9(reason) => ortho9(reason),
        DeviceError::InvalidCalibration(reason) => {
            format!("the device refused the calibration: {}", calibration_reason(&reason))
        }
        _ => board(error),
    }
}

fn sensor(error: &DeviceError) -> String {
    match *error {
        DeviceError::SensorMissing => "the MPU-6050 does not answer at 0x68 or 0x69: check VCC, GND, SCL (PB6) and SDA (PB7) and the pull-ups".into(),
        DeviceError::UnknownSensor { address, who_am_i } => format!("the chip at 0x{address:02x} is not an MPU-6050 (WHO_AM_I 0x{who_am_i:02x}); check the module"),
        DeviceError::Bus => "an I2C transfer to the sensor failed: check the wiring and the pull-ups, then try again".into(),
        _ => "the sensor FIFO overflowed and samples were lost: the board was too busy; try again, or lower the sample rate".into(),
    }
}

fn capture(error: &DeviceError) -> String {
    match *error {
        DeviceError::Moved { accel_std_mg, gyro_std_dps } => format!("the board moved during the capture (scatter {accel_std_mg:.1} mg, {gyro_std_dps:.2} deg/s): rest it against something firm and keep still"),
        DeviceError::Clipped { samples } => format!("{samples} samples hit the end of the range: the board was knocked, or choose a wider range"),
        DeviceError::InvalidDuration { seconds } => format!("a capture of {seconds} s is not possible: choose {MIN_CAPTURE_SECONDS} to {MAX_CAPTURE_SECONDS} s"),
        DeviceError::InvalidRate { rate_hz } => format!("{rate_hz} Hz is not possible: choose a rate that divides the 1 kHz sensor clock (and, for a stream, the sample rate)"),
        _ => "the operation was cancelled".into(),
    }
}

fn six_position(reason: SixPositionError) -> String {
    match reason {
        SixPositionError::Missing(p) => {
            format!("the six-position fit needs a capture with {} up: capture it first", p.name())
        }
        SixPositionError::Degenerate => {
            "the six captures do not determine the sensor: opposite faces read alike; capture them again".into()
        }
    }
}

/// Why the chip's 9-parameter fit could not run on the captures it kept.
fn ortho9(reason: Ortho9Error) -> String {
    match reason {
        Ortho9Error::TooFewReadings(n) => format!(
            "the chip's 9-parameter fit needs at least {MIN_READINGS} captures and it holds {n}: capture more positions (a restart or a range change forgets them)"
        ),
        Ortho9Error::IllConditioned(k) => format!(
            "the chip's captures do not determine {} (they lie too close together): capture positions spread over the sphere, the faces and the corners asked for",
            PARAMETER_NAMES.get(usize::from(k)).copied().unwrap_or("a parameter")
        ),
        Ortho9Error::NotConverged => "the chip's 9-parameter fit did not settle: the captures disagree (did the board move, or the range change?); capture them again".into(),
        Ortho9Error::NotFinite => "the chip's captures hold a value that is not a number: check the sensor and capture them again".into(),
    }
}

/// The `ortho9` parameters in the solver's order, as the host's fit names them.
const PARAMETER_NAMES: [&str; 9] = [
    "the cross-axis term a_yz",
    "the cross-axis term a_zy",
    "the cross-axis term a_zx",
    "the x scale",
    "the y scale",
    "the z scale",
    "the x offset",
    "the y offset",
    "the z offset",
];

fn board(error: &DeviceError) -> String {
    match *error {
        DeviceError::RangeMismatch { calibration, configured } => format!(
            "the calibration is for +-{} g but the sensor is at +-{} g: configure the range first",
            calibration.full_scale_g(),
            configured.full_scale_g()
        ),
        DeviceError::NoCalibration => "there is no calibration to save: fit or upload one first".into(),
        DeviceError::Storage => {
            "the board could not read or write its flash: try again; if it persists, erase the calibration".into()
        }
        DeviceError::Busy => "the device is busy with another capture or stream: wait for it, or cancel it".into(),
        DeviceError::Frame(frame) => {
            format!("the device could not read a message ({}); the cable may be bad", frame_reason(&frame))
        }
        DeviceError::UnsupportedVersion { device, host } => {
            format!("protocol version mismatch: device {device}, host {host}")
        }
        DeviceError::InvalidGoal => format!(
            "the device refused the capture's stop rule (it takes {} samples to {} s at the sample rate, and a \
             positive goal): update the host tool to the firmware's version",
            shared::protocol::MIN_GOAL_SAMPLES,
            shared::protocol::MAX_CAPTURE_SECONDS
        ),
        _ => format!("the device reported {error:?}"),
    }
}

fn frame_reason(error: &FrameError) -> String {
    match error {
        FrameError::Oversized => "too long".into(),
        FrameError::Cobs | FrameError::Payload => "garbled".into(),
        FrameError::Truncated => "cut short".into(),
        FrameError::Crc => "checksum mismatch".into(),
        FrameError::Version { got } => format!("protocol version {got}, expected {PROTOCOL_VERSION}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_impossible_capture_length_names_the_lengths_possible() {
        let duration = explain(&DeviceError::InvalidDuration { seconds: 3 });
        assert_eq!(duration, "a capture of 3 s is not possible: choose 5 to 20 s");
    }

    #[test]
    fn the_chip_s_ortho9_refusals_name_the_count_and_the_parameter() {
        let few = explain(&DeviceError::Ortho9(Ortho9Error::TooFewReadings(6)));
        assert!(few.starts_with("the chip's 9-parameter fit needs at least 9 captures and it holds 6: "), "{few}");
        let alike = explain(&DeviceError::Ortho9(Ortho9Error::IllConditioned(2)));
        assert!(alike.starts_with("the chip's captures do not determine the cross-axis term a_zx "), "{alike}");
    }
}
