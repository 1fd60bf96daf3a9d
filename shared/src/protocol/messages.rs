//! Request, response and error messages (serde + postcard).

use serde::{Deserialize, Serialize};

use crate::calibration::{AccelRange, Calibration, CalibrationError};
use crate::orientation::{Position, PositionMap};
use crate::ortho9::Ortho9Error;
use crate::part::{Family, Identification, Part};
use crate::selftest::SelfTestRecord;
use crate::six_position::SixPositionError;

use super::FrameError;

/// What the host asks of the device.
// NOTE: a calibration makes one variant large; without an allocator it cannot be boxed, and a
// message is built once and handed on, so the size costs RAM in the outbox, not time.
#[allow(clippy::large_enum_variant)]
#[derive(Serialize, Deserialize, Debug, Clone, PartialEq)]
pub enum Request {
    /// Sets range, sample rate and filter; answered with [`Response::Configured`] (the rate achieved).
    Configure(SensorConfig),
    /// Averages the still sensor for `seconds` (see [`super::MIN_CAPTURE_SECONDS`]); progress, then
    /// [`Response::Captured`].
    Capture { seconds: u8 },
    /// Stops the running capture or stream; the stopped operation ends with an error or its end message.
    Cancel,
    /// Forgets the captures kept for the chip's fits (six-position and `ortho9`).
    ClearPositions,
    /// Fits the six-position closed form on the chip from the kept captures and returns it; the active
    /// calibration is untouched (send [`Request::SetCalibration`] to make the fit active).
    FitSixPosition,
    /// Reads the active (RAM) or the stored (flash) calibration.
    GetCalibration(CalibrationSlot),
    /// Makes a calibration active after validating it; the stored one is untouched until saved.
    SetCalibration(Calibration),
    /// Writes the active calibration to flash.
    SaveCalibration,
    /// Erases the stored calibration and returns the active one to identity.
    EraseCalibration,
    /// Streams `count` samples (0: until cancelled) at `rate_hz`, raw or calibrated.
    Stream { kind: StreamKind, rate_hz: u16, count: u32 },
    /// Hands over and empties the coolest temperature bins (at most
    /// [`super::TEMP_BINS_PER_MESSAGE`]); answered with [`Response::TemperatureBins`]. Allowed
    /// during a capture or stream.
    TakeTemperatureBins,
    /// Fits the 9-parameter orientation-free model (`ortho9`, in f32) on the chip to the captures it
    /// kept (the latest [`super::MAX_KEPT_CAPTURES`] since [`Request::ClearPositions`]), wherever they
    /// were taken, and returns it as [`Response::Ortho9Fitted`]; the active calibration is untouched.
    FitOrtho9,
    /// Averages the still sensor until its mean is known well enough (see [`CaptureGoal`]); progress,
    /// then [`Response::Captured`], whose `samples` tell whether the goal or the maximum ended it.
    CaptureUntil(CaptureGoal),
    /// Writes `write` to a sensor register when given, then reads the register; answered with
    /// [`Response::Register`]. Refused while a capture or stream runs. The board's own configuration
    /// stays as it was: [`Request::Configure`] and every [`Request::Hello`] write it to the sensor again.
    // NOTE: one register a request, read and write in one: a buffer of registers and a second
    // request cost the board more flash than the Pico has left; a dump of the map is 127 requests.
    Register { register: u8, write: Option<u8> },
    /// Keeps a self-test's result ([`crate::selftest::StoredSelfTest::record`]) in flash beside the calibration, in place of the one before (a
    /// calibration's save or erase leaves it as it is); answered with [`Response::Done`]. Refused
    /// while a capture or stream runs. Every [`Response::Hello`] carries it
    /// ([`DeviceInfo::self_test`]).
    StoreSelfTest(SelfTestRecord),
    /// Opens a session; answered with [`Response::Hello`]. Sent first.
    // NOTE: last, so that its index (postcard's first payload byte) is no byte a REPL acts on: the
    // hello is what accelcal writes to a port it does not know yet (`crate::protocol::probe`).
    Hello { protocol_version: u8 },
}

/// When a [`Request::CaptureUntil`] stops: once at least `min_samples` are averaged and the standard
/// error of the mean (sample standard deviation / sqrt(n)) of every accelerometer axis is at most
/// `mean_std_g`, or at `max_samples` whatever it shows. `min_samples == max_samples` is a fixed length.
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq)]
pub struct CaptureGoal {
    /// Standard error of each axis' mean to reach, in g.
    pub mean_std_g: f32,
    /// Fewest samples to average (at least [`super::MIN_GOAL_SAMPLES`]).
    pub min_samples: u32,
    /// Most samples to average (at most [`super::MAX_CAPTURE_SECONDS`] at the sample rate).
    pub max_samples: u32,
}

/// What the device answers.
// NOTE: a calibration makes one variant large; without an allocator it cannot be boxed, and a
// message is built once and handed on, so the size costs RAM in the outbox, not time.
#[allow(clippy::large_enum_variant)]
#[derive(Serialize, Deserialize, Debug, Clone, PartialEq)]
pub enum Response {
    /// Answer to [`Request::Hello`].
    Hello(DeviceInfo),
    /// The configuration now in force.
    Configured(SensorConfig),
    /// A capture is running (sent at least once a second).
    Progress(CaptureProgress),
    /// A capture finished; `position` is the face it was detected at, if it was at one.
    Captured { stats: CaptureStats, position: Option<Position> },
    /// The on-chip six-position fit (not active: see [`Request::FitSixPosition`]).
    Fitted(Calibration),
    /// The requested calibration, `None` when there is none.
    Calibration(Option<Calibration>),
    /// One streamed sample.
    Sample(Sample),
    /// A stream ended: `samples` were sent, `dropped` more were taken but had to be dropped because
    /// the outbox was full (the host read too slowly); their sequence numbers are the gaps.
    StreamEnded { samples: u32, dropped: u32 },
    /// The request was carried out and has nothing to report.
    Done,
    /// The request failed; nothing was changed unless the error says so.
    Error(DeviceError),
    /// Temperature bins, coolest first, now emptied on the chip; fewer than
    /// [`super::TEMP_BINS_PER_MESSAGE`] means none are left.
    TemperatureBins(heapless::Vec<super::TempBin, { super::TEMP_BINS_PER_MESSAGE }>),
    /// Answer to [`Request::FitOrtho9`]: the fit (its `residual_mg` is the RMS of |a| - 1 g over
    /// the captures, in mg), how many captures it used and the solver's iterations. Not active.
    Ortho9Fitted { calibration: Calibration, captures: u8, iterations: u8 },
    /// Answer to [`Request::Register`]: the register's value.
    Register(u8),
}

/// Which copy of the calibration to read.
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq, Eq)]
pub enum CalibrationSlot {
    /// The calibration applied to samples now (RAM).
    Active,
    /// The calibration in flash, loaded at boot.
    Stored,
}

/// Whether streamed samples are corrected.
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq, Eq)]
pub enum StreamKind {
    /// Sensor output converted to g and deg/s, uncorrected.
    Raw,
    /// Corrected with the active calibration at the sample's temperature: a = M(T) (m - o(T)),
    /// w = G (w_raw - b(T)).
    Calibrated,
}

/// The MPU-6050 digital low-pass filter setting (register CONFIG, DLPF_CFG), by accelerometer bandwidth.
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq, Eq, Default)]
// NOTE: a JSON file spells each variant as a person reads it (issue 40: sessions said "G2", "Hz44",
// "HostFit"); the old spellings are still read. postcard (the wire and the flash) keeps the variant's
// index, so the renames change no byte there.
pub enum LowPassFilter {
    /// 260 Hz (filter off).
    #[serde(rename = "260Hz", alias = "Hz260")]
    Hz260,
    /// 184 Hz.
    #[serde(rename = "184Hz", alias = "Hz184")]
    Hz184,
    /// 94 Hz.
    #[serde(rename = "94Hz", alias = "Hz94")]
    Hz94,
    /// 44 Hz (the default).
    #[default]
    #[serde(rename = "44Hz", alias = "Hz44")]
    Hz44,
    /// 21 Hz.
    #[serde(rename = "21Hz", alias = "Hz21")]
    Hz21,
    /// 10 Hz.
    #[serde(rename = "10Hz", alias = "Hz10")]
    Hz10,
    /// 5 Hz.
    #[serde(rename = "5Hz", alias = "Hz5")]
    Hz5,
}

impl LowPassFilter {
    /// The accelerometer bandwidth, in Hz (Register Map 4.3).
    pub fn bandwidth_hz(self) -> u16 {
        match self {
            LowPassFilter::Hz260 => 260,
            LowPassFilter::Hz184 => 184,
            LowPassFilter::Hz94 => 94,
            LowPassFilter::Hz44 => 44,
            LowPassFilter::Hz21 => 21,
            LowPassFilter::Hz10 => 10,
            LowPassFilter::Hz5 => 5,
        }
    }
}

/// Sensor settings.
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq, Eq)]
pub struct SensorConfig {
    /// Accelerometer full-scale range.
    pub range: AccelRange,
    /// Sample rate in Hz (the device answers with the rate it achieves).
    pub sample_rate_hz: u16,
    /// Digital low-pass filter.
    pub filter: LowPassFilter,
}

impl Default for SensorConfig {
    fn default() -> Self {
        SensorConfig { range: AccelRange::G2, sample_rate_hz: 100, filter: LowPassFilter::Hz44 }
    }
}

/// The version of the firmware, from its Cargo package version.
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq, Eq)]
pub struct FirmwareVersion {
    pub major: u8,
    pub minor: u8,
    pub patch: u8,
}

/// Which chip answered, where, and the register family it behaves as.
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq, Eq)]
pub struct SensorIdentity {
    /// 7-bit I2C address, 0x68 or 0x69.
    pub address: u8,
    /// The WHO_AM_I register (0x75) value.
    pub who_am_i: u8,
    /// The family the chip behaves as (its registers, not its WHO_AM_I), as the board configures it.
    pub family: Family,
}

impl SensorIdentity {
    /// The part its WHO_AM_I names and the family it behaves as.
    pub fn identification(&self) -> Identification {
        Identification { part: Part::from_who_am_i(self.who_am_i), family: self.family }
    }
}

/// Where the active calibration came from.
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq, Eq)]
pub enum ActiveCalibration {
    /// No calibration: samples pass through uncorrected.
    None,
    /// The calibration stored in flash.
    Stored,
    /// A calibration fitted or uploaded since boot and not saved.
    Unsaved,
}

/// The device's answer to [`Request::Hello`].
#[derive(Serialize, Deserialize, Debug, Clone, PartialEq)]
pub struct DeviceInfo {
    /// The device's protocol version.
    pub protocol_version: u8,
    /// The board's serial number (also its USB serial number).
    pub serial: SerialNumber,
    /// The firmware version.
    pub firmware: FirmwareVersion,
    /// The sensor found at boot, or the error that prevented finding it.
    pub sensor: Result<SensorIdentity, DeviceError>,
    /// The sensor configuration in force.
    pub config: SensorConfig,
    /// Where the active calibration came from.
    pub active: ActiveCalibration,
    /// Whether flash holds a calibration.
    pub stored: bool,
    /// The positions whose captures are kept for the six-position fit.
    pub positions: PositionMap<()>,
    /// The latest self-test kept in flash ([`Request::StoreSelfTest`]), if any, as the host stored it.
    pub self_test: Option<SelfTestRecord>,
}

/// Length of the STM32's unique device ID (RM0383 section 24.2), in bytes.
pub const SERIAL_NUMBER_LEN: usize = 12;

/// A board's serial number: the STM32's 96-bit unique device ID (the simulated board's is derived
/// from its seed). Shown as 24 hexadecimal digits, the same in the USB descriptor and in sessions.
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct SerialNumber(pub [u8; SERIAL_NUMBER_LEN]);

impl SerialNumber {
    /// The 24 upper-case hexadecimal digits, in ASCII, most significant byte of the ID first.
    pub fn hex(&self) -> [u8; 2 * SERIAL_NUMBER_LEN] {
        const DIGITS: &[u8; 16] = b"0123456789ABCDEF";
        let mut text = [0u8; 2 * SERIAL_NUMBER_LEN];
        for (pair, byte) in text.chunks_exact_mut(2).zip(self.0) {
            pair[0] = DIGITS[usize::from(byte >> 4)];
            pair[1] = DIGITS[usize::from(byte & 0x0F)];
        }
        text
    }
}

/// How far a running capture has got.
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq)]
pub struct CaptureProgress {
    /// Samples averaged so far.
    pub samples: u32,
    /// Samples the capture will average in all.
    pub total_samples: u32,
    /// Mean of the samples so far, in g, for a live display.
    pub mean_g: [f32; 3],
}

/// The statistics of one capture of the still sensor.
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq)]
pub struct CaptureStats {
    /// Number of samples averaged.
    pub samples: u32,
    /// Capture duration in seconds (samples / sample rate).
    pub seconds: f32,
    /// Mean accelerometer reading per axis, in g.
    pub mean_g: [f32; 3],
    /// Standard deviation of the accelerometer samples per axis, in g.
    pub std_g: [f32; 3],
    /// Mean gyro reading per axis, in deg/s.
    pub gyro_mean_dps: [f32; 3],
    /// Standard deviation of the gyro samples per axis, in deg/s.
    pub gyro_std_dps: [f32; 3],
    /// Mean die temperature in degC.
    pub temp_c: f32,
    /// Samples with an axis at the end of the range.
    pub clipped: u32,
    /// The range the capture was taken at.
    pub range: AccelRange,
}

/// One streamed sample.
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// Sequence number within the stream, from 0: every sample the stream took counts, sent or
    /// dropped, so a missing number is a lost sample.
    pub index: u32,
    /// The sensor's sample time since the stream started, in microseconds: FIFO samples counted at
    /// the sample rate (decimated-away samples count too), so it runs on the sensor's own clock.
    pub time_us: u64,
    /// Specific force in g (corrected when the stream is calibrated).
    pub accel_g: [f32; 3],
    /// Angular rate in deg/s (corrected when the stream is calibrated).
    pub gyro_dps: [f32; 3],
    /// Die temperature in degC.
    pub temp_c: f32,
}

/// Why the device refused or failed a request. Typed, so the host can name cause and remedy.
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq)]
pub enum DeviceError {
    /// No device acknowledges at 0x68 or 0x69.
    SensorMissing,
    /// A device answers but its WHO_AM_I is not an MPU-6050 or a known clone.
    UnknownSensor { address: u8, who_am_i: u8 },
    /// An I2C transaction failed.
    Bus,
    /// The sensor FIFO overflowed, so samples were lost.
    FifoOverflow,
    /// The board moved during the capture: the scatter exceeded [`super::MAX_STILL_ACCEL_STD_G`] or
    /// [`super::MAX_STILL_GYRO_STD_DPS`].
    Moved { accel_std_mg: f32, gyro_std_dps: f32 },
    /// Samples reached the end of the range.
    Clipped { samples: u32 },
    /// The operation was cancelled by the host.
    Cancelled,
    /// A capture length outside [`super::MIN_CAPTURE_SECONDS`]..=[`super::MAX_CAPTURE_SECONDS`].
    InvalidDuration { seconds: u8 },
    /// A sample rate the sensor cannot run at, or a stream rate above the sample rate.
    InvalidRate { rate_hz: u16 },
    /// The six-position fit cannot run.
    SixPosition(SixPositionError),
    /// A calibration was refused.
    InvalidCalibration(CalibrationError),
    /// The calibration belongs to another range than the one configured.
    RangeMismatch { calibration: AccelRange, configured: AccelRange },
    /// There is no calibration to save.
    NoCalibration,
    /// Reading or writing flash failed.
    Storage,
    /// Another long operation is running.
    Busy,
    /// A frame could not be read; it was not acted on.
    Frame(FrameError),
    /// The host speaks another protocol version.
    UnsupportedVersion { device: u8, host: u8 },
    /// The chip's 9-parameter fit cannot run on the captures it kept: too few, or too alike.
    Ortho9(Ortho9Error),
    /// A [`CaptureGoal`] outside its limits: a goal that is not positive, fewer than
    /// [`super::MIN_GOAL_SAMPLES`], more than [`super::MAX_CAPTURE_SECONDS`] at the rate, or min above max.
    InvalidGoal,
}
