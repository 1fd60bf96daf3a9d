//! The device: answers every request with exactly one final response, runs captures and streams,
//! fits its captures (six positions, or the 9-parameter model on any captures), and keeps the calibration active in RAM and stored in flash.
//!
//! Target-independent: the board binary feeds it decoded requests and polls it every few
//! milliseconds; tests and the host's simulated device do the same on the simulated MPU-6050.
//!
//! Split by concern: [`dispatch`] routes requests, [`jobs`] runs the long operations (capture,
//! stream), [`slots`] keeps the active and stored calibration, [`fit`] keeps captures for the chip's
//! 9-parameter fit and runs it, [`sample`] turns a sensor reading into a message.

mod dispatch;
mod fit;
mod jobs;
mod sample;
mod slots;

use core::ops::Range;

use embedded_hal_async::i2c::I2c;
use embedded_storage_async::nor_flash::NorFlash;
use heapless::Deque;
use shared::protocol::{
    ActiveCalibration, CaptureStats, DeviceError, FirmwareVersion, FrameError, Response, SensorConfig, SerialNumber,
};
use shared::selftest::SelfTestRecord;
use shared::{Calibration, PositionMap};

use crate::sensor::{self, Sensor};
use crate::storage::{Storage, StorageError};
use crate::temperature_bins::TemperatureBins;

pub use sample::sample_message;

/// Responses waiting to be sent: enough for a poll's worth of streamed samples.
pub const OUTBOX_LEN: usize = 16;

/// The firmware version, from the package version.
pub const FIRMWARE_VERSION: FirmwareVersion = FirmwareVersion {
    major: parse_u8(env!("CARGO_PKG_VERSION_MAJOR")),
    minor: parse_u8(env!("CARGO_PKG_VERSION_MINOR")),
    patch: parse_u8(env!("CARGO_PKG_VERSION_PATCH")),
};

/// The device state machine over an I2C bus `I` and a flash `F`.
pub struct Device<I, F: NorFlash> {
    bus: I,
    serial: SerialNumber,
    sensor: Result<Sensor, DeviceError>,
    config: SensorConfig,
    storage: Storage<F>,
    stored: bool,
    /// The latest self-test in flash, as every hello reports it.
    self_test: Option<SelfTestRecord>,
    active: Calibration,
    source: ActiveCalibration,
    /// The latest capture at each face, kept for the six-position fit.
    positions: PositionMap<CaptureStats>,
    /// Every sample captures and streams took, by whole degree, until the host takes them.
    temperature_bins: TemperatureBins,
    /// The latest captures wherever they were taken, kept for the 9-parameter fit.
    kept: fit::KeptCaptures,
    job: jobs::Job,
    outbox: Deque<(u16, Response), OUTBOX_LEN>,
}

impl<I, F> Device<I, F>
where
    I: I2c,
    F: NorFlash,
{
    /// Boots the board `serial`: finds and configures the sensor, loads the stored calibration from
    /// `range` of `flash`.
    pub async fn boot(bus: I, flash: F, range: Range<u32>, serial: SerialNumber) -> Result<Self, StorageError> {
        let mut storage = Storage::new(flash, range)?;
        let loaded = storage.load().await;
        // NOTE: a damaged self-test record costs only the trend; the next self-test writes a new one.
        let self_test = storage.load_self_test().await.ok().flatten();
        let config = SensorConfig::default();
        let mut device = Device {
            bus,
            serial,
            sensor: Err(DeviceError::SensorMissing),
            config,
            storage,
            stored: matches!(loaded, Ok(Some(_))),
            self_test,
            active: Calibration::identity(config.range),
            source: ActiveCalibration::None,
            positions: PositionMap::new(),
            temperature_bins: TemperatureBins::default(),
            kept: fit::KeptCaptures::default(),
            job: jobs::Job::Idle,
            outbox: Deque::new(),
        };
        if let Ok(Some(calibration)) = loaded {
            device.active = calibration;
            device.source = ActiveCalibration::Stored;
        }
        let _ = device.sensor().await;
        Ok(device)
    }

    /// The I2C bus (the simulated sensor, in tests).
    pub fn bus_mut(&mut self) -> &mut I {
        &mut self.bus
    }

    /// The board's serial number.
    pub fn serial(&self) -> SerialNumber {
        self.serial
    }

    /// The calibration applied to samples now.
    pub fn active_calibration(&self) -> Option<Calibration> {
        (self.source != ActiveCalibration::None).then_some(self.active)
    }

    /// Whether a capture or a stream is running.
    pub fn is_busy(&self) -> bool {
        self.job != jobs::Job::Idle
    }

    /// Takes the device apart, to reboot it on the same bus and flash.
    pub fn into_parts(self) -> (I, F) {
        (self.bus, self.storage.into_flash())
    }

    /// The next response to send, if any.
    pub fn next_response(&mut self) -> Option<(u16, Response)> {
        self.outbox.pop_front()
    }

    /// Answers a frame that could not be read; its request id is unknown.
    pub fn reject_frame(&mut self, error: FrameError) {
        self.send(shared::protocol::frame::UNKNOWN_REQUEST_ID, Response::Error(DeviceError::Frame(error)));
    }

    fn send(&mut self, request_id: u16, response: Response) {
        // NOTE: the outbox is drained after every request and poll, and polls take no more samples
        // than it has room for; a full outbox would only drop this message, never block.
        let _ = self.outbox.push_back((request_id, response));
    }

    /// The sensor, found again if it was missing (a loose wire put back).
    async fn sensor(&mut self) -> Result<&mut Sensor, DeviceError> {
        if self.sensor.is_err() {
            self.sensor = self.find_sensor().await.map_err(|e| e.to_device_error());
        }
        self.sensor.as_mut().map_err(|e| *e)
    }

    /// Probes for the sensor and configures it as the device is configured.
    async fn find_sensor(&mut self) -> Result<Sensor, sensor::Error<I::Error>> {
        let mut sensor = Sensor::probe(&mut self.bus).await?;
        sensor.configure(&mut self.bus, self.config).await?;
        Ok(sensor)
    }

    /// Records a bus failure and looks for the sensor again at once: a sensor that no longer answers
    /// is reported as missing, a passing fault as the bus error it was.
    async fn sensor_failed(&mut self, error: sensor::Error<I::Error>) -> DeviceError {
        let error = error.to_device_error();
        if error == DeviceError::Bus {
            self.sensor = Err(DeviceError::Bus);
            if let Err(missing) = self.sensor().await {
                return missing;
            }
        }
        error
    }

    /// Runs one driver operation on the sensor (found again first if it was missing); the samples
    /// a FIFO read took, the value a register read, 0 for the others.
    ///
    /// NOTE: an operation is data, not a closure: one instance of this state machine, with its
    /// sensor recovery, serves every operation (closures cost 400 bytes of flash each).
    async fn with_sensor(&mut self, operation: SensorOp<'_>) -> Result<usize, DeviceError> {
        self.sensor().await?;
        let (sensor, bus) = match self.sensor.as_mut() {
            Ok(sensor) => (sensor, &mut self.bus),
            Err(error) => return Err(*error),
        };
        let result = match operation {
            SensorOp::Configure(config) => sensor.configure(bus, config).await.map(|_| 0),
            SensorOp::StartFifo => sensor.start_fifo(bus).await.map(|()| 0),
            SensorOp::ReadFifo(batch) => sensor.read_fifo(bus, batch).await,
            SensorOp::Register(register, write) => sensor.register(bus, register, write).await.map(usize::from),
        };
        match result {
            Ok(samples) => Ok(samples),
            Err(e) => Err(self.sensor_failed(e).await),
        }
    }
}

/// A driver operation the device runs through [`Device::with_sensor`].
enum SensorOp<'a> {
    /// Applies a configuration; the sensor keeps the one achieved.
    Configure(SensorConfig),
    /// Starts the FIFO afresh.
    StartFifo,
    /// Reads whole samples from the FIFO into the batch.
    ReadFifo(&'a mut [crate::sensor::RawSample]),
    /// Writes the value to the register when there is one, then reads the register.
    Register(u8, Option<u8>),
}

/// Parses a decimal version component at compile time (0 when it is not a number below 256).
const fn parse_u8(text: &str) -> u8 {
    let bytes = text.as_bytes();
    let mut value: u32 = 0;
    let mut i = 0;
    while i < bytes.len() {
        if !bytes[i].is_ascii_digit() || value > 25 {
            return 0;
        }
        value = value * 10 + (bytes[i] - b'0') as u32;
        i += 1;
    }
    if value > 255 {
        0
    } else {
        value as u8
    }
}

#[cfg(test)]
mod tests;

#[cfg(test)]
mod fault_tests;

#[cfg(test)]
mod guard_tests;

#[cfg(test)]
mod fit_tests;

#[cfg(test)]
mod stream_tests;

#[cfg(test)]
mod bin_tests;
