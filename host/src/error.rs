//! The host library's errors: each names the cause and what to do about it.

use std::fmt;

use shared::protocol::{DeviceError, FrameError, MAX_CAPTURE_SECONDS, MIN_CAPTURE_SECONDS, PROTOCOL_VERSION};
use shared::{CalibrationError, SixPositionError};

use crate::data::DataError;
use crate::fit::FitError;

/// Everything that can go wrong talking to a device or handling a calibration.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    #[error("cannot open {port}: {reason}; check the cable and the path (`accelcal ports` lists the ports)")]
    Open { port: String, reason: String },
    #[error("no answer from the device within {seconds} s: is it an accelcal board running the firmware? (reflash it, or unplug and replug it)")]
    Silent { seconds: f64 },
    #[error("the device stopped answering in the middle of the operation: it restarted or lost power; check the cable and the power, then run the command again")]
    StoppedAnswering,
    #[error("the device went away ({reason}): it was unplugged or restarted; reconnect and run the command again")]
    Disconnected { reason: String },
    #[error("the device speaks protocol version {device}, this accelcal speaks {host}: update {}", if device < host { "the firmware (cargo run --release in firmware/)" } else { "accelcal" })]
    Version { device: u8, host: u8 },
    #[error("{}", explain(.0))]
    Device(DeviceError),
    #[error("unexpected answer from the device: {0}")]
    Protocol(String),
    #[error("{context}: {source}")]
    Io { context: String, source: std::io::Error },
    #[error(transparent)]
    Data(#[from] DataError),
    #[error(transparent)]
    Fit(#[from] FitError),
    #[error("{0}")]
    Refused(String),
}

impl From<DeviceError> for Error {
    fn from(error: DeviceError) -> Self {
        match error {
            DeviceError::UnsupportedVersion { device, host } => Error::Version { device, host },
            other => Error::Device(other),
        }
    }
}

/// One line: what the device said went wrong, and what to do.
pub fn explain(error: &DeviceError) -> String {
    match *error {
        DeviceError::SensorMissing => "the MPU-6050 does not answer at 0x68 or 0x69: check VCC, GND, SCL (PB6) and SDA (PB7) and the pull-ups".into(),
        DeviceError::UnknownSensor { address, who_am_i } => format!("the chip at 0x{address:02x} is not an MPU-6050 (WHO_AM_I 0x{who_am_i:02x}); check the module"),
        DeviceError::Bus => "an I2C transfer to the sensor failed: check the wiring and the pull-ups, then try again".into(),
        DeviceError::FifoOverflow => "the sensor FIFO overflowed and samples were lost: the board was too busy; try again, or lower the sample rate".into(),
        DeviceError::Moved { accel_std_mg, gyro_std_dps } => format!("the board moved during the capture (scatter {accel_std_mg:.1} mg, {gyro_std_dps:.2} deg/s): rest it against something firm and keep still"),
        DeviceError::Clipped { samples } => format!("{samples} samples hit the end of the range: the board was knocked, or choose a wider range"),
        DeviceError::Cancelled => "the operation was cancelled".into(),
        DeviceError::InvalidDuration { seconds } => format!("a capture of {seconds} s is not possible: choose {MIN_CAPTURE_SECONDS} to {MAX_CAPTURE_SECONDS} s"),
        DeviceError::InvalidRate { rate_hz } => format!("{rate_hz} Hz is not possible: choose a rate that divides the 1 kHz sensor clock (and, for a stream, the sample rate)"),
        DeviceError::SixPosition(SixPositionError::Missing(p)) => format!("the six-position fit needs a capture with {} up: capture it first", p.name()),
        DeviceError::SixPosition(SixPositionError::Degenerate) => "the six captures do not determine the sensor: opposite faces read alike; capture them again".into(),
        DeviceError::InvalidCalibration(reason) => format!("the device refused the calibration: {}", calibration_reason(&reason)),
        DeviceError::RangeMismatch { calibration, configured } => format!("the calibration is for +-{} g but the sensor is at +-{} g: configure the range first", calibration.full_scale_g(), configured.full_scale_g()),
        DeviceError::NoCalibration => "there is no calibration to save: fit or upload one first".into(),
        DeviceError::Storage => "the board could not read or write its flash: try again; if it persists, erase the calibration".into(),
        DeviceError::Busy => "the device is busy with another capture or stream: wait for it, or cancel it".into(),
        DeviceError::Frame(frame) => format!("the device could not read a message ({}); the cable may be bad", frame_reason(&frame)),
        DeviceError::UnsupportedVersion { device, host } => format!("protocol version mismatch: device {device}, host {host}"),
    }
}

/// Why a calibration was refused, in words; the limits are quoted from shared's one table.
pub fn calibration_reason(reason: &CalibrationError) -> String {
    use shared::calibration::limits::*;
    let axis = |a: u8| ["x", "y", "z"].get(usize::from(a)).copied().unwrap_or("?");
    let (low_c, high_c) = OPERATING_TEMP_C;
    let over = format!("somewhere in {low_c}..{high_c} degC");
    match *reason {
        CalibrationError::NonFinite => "it holds a value that is not a number".into(),
        CalibrationError::Singular { determinant } => format!("its matrix is singular (determinant {determinant:.3})"),
        CalibrationError::ScaleOutOfRange { axis: a, value } => {
            format!("the {} scale {value:.3} is outside {}-{}", axis(a), SCALE.0, SCALE.1)
        }
        CalibrationError::CrossAxisOutOfRange { row, col, value } => {
            format!("cross-axis term M{}{} = {value:.3} is larger than {CROSS_AXIS}", row + 1, col + 1)
        }
        CalibrationError::OffsetOutOfRange { axis: a, value_g } => {
            format!("the {} offset {value_g:.3} g is larger than {OFFSET_G} g", axis(a))
        }
        CalibrationError::GyroBiasOutOfRange { axis: a, value_dps } => {
            format!("the {} gyro bias {value_dps:.1} deg/s is larger than {GYRO_BIAS_DPS} deg/s", axis(a))
        }
        CalibrationError::GyroSingular { determinant } => {
            format!("its gyro matrix is singular (determinant {determinant:.3})")
        }
        CalibrationError::GyroScaleOutOfRange { axis: a, value } => {
            format!("the {} gyro scale {value:.3} is outside {}-{}", axis(a), GYRO_SCALE.0, GYRO_SCALE.1)
        }
        CalibrationError::GyroCrossAxisOutOfRange { row, col, value } => {
            format!("gyro cross-axis term G{}{} = {value:.3} is larger than {GYRO_CROSS_AXIS}", row + 1, col + 1)
        }
        CalibrationError::ReferenceTemperatureOutOfRange { value_c } => {
            format!("its reference temperature {value_c:.1} degC is outside {low_c}..{high_c} degC")
        }
        CalibrationError::OffsetDriftOutOfRange { axis: a, value_g } => {
            format!("the {} offset drifts by {value_g:.3} g {over}, more than {OFFSET_DRIFT_G} g", axis(a))
        }
        CalibrationError::ScaleDriftOutOfRange { axis: a, value } => {
            format!("the {} scale drifts by {value:.3} {over}, more than {SCALE_DRIFT}", axis(a))
        }
        CalibrationError::GyroBiasDriftOutOfRange { axis: a, value_dps } => {
            format!(
                "the {} gyro bias drifts by {value_dps:.1} deg/s {over}, more than {GYRO_BIAS_DRIFT_DPS} deg/s",
                axis(a)
            )
        }
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

impl Error {
    /// An I/O error with what was being done.
    pub fn io(context: impl fmt::Display, source: std::io::Error) -> Self {
        Error::Io { context: context.to_string(), source }
    }
}
