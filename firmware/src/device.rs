//! The device: answers every request with exactly one final response, runs captures and streams,
//! fits six positions, and keeps the calibration active in RAM and stored in flash.
//!
//! Target-independent: the board binary feeds it decoded requests and polls it every few
//! milliseconds; tests and the host's simulated device do the same on the simulated MPU-6050.

use core::ops::Range;

use embedded_hal::blocking::i2c::{Write, WriteRead};
use embedded_storage_async::nor_flash::NorFlash;
use heapless::Deque;
use shared::orientation::DEFAULT_FACE_TOLERANCE_DEG;
use shared::protocol::{
    ActiveCalibration, CalibrationSlot, CaptureStats, DeviceError, DeviceInfo, FirmwareVersion, FrameError,
    PositionSet, Request, Response, Sample, SensorConfig, StreamKind, PROTOCOL_VERSION,
};
use shared::{Calibration, Model, Position, PositionReadings};

use crate::capture::Capture;
use crate::sensor::{self, RawSample, Sensor};
use crate::storage::{Storage, StorageError};

/// Responses waiting to be sent: enough for a poll's worth of streamed samples.
pub const OUTBOX_LEN: usize = 16;
/// Samples read from the FIFO per read in a poll.
const READ_BATCH: usize = 16;

/// The firmware version, from the package version.
pub const FIRMWARE_VERSION: FirmwareVersion = FirmwareVersion {
    major: parse_u8(env!("CARGO_PKG_VERSION_MAJOR")),
    minor: parse_u8(env!("CARGO_PKG_VERSION_MINOR")),
    patch: parse_u8(env!("CARGO_PKG_VERSION_PATCH")),
};

/// A long operation in progress.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Job {
    Idle,
    Capturing { request_id: u16, capture: Capture, next_progress: u32 },
    Streaming { request_id: u16, kind: StreamKind, decimation: u32, remaining: Option<u32>, sent: u32, skip: u32 },
}

/// The device state machine over an I2C bus `I` and a flash `F`.
pub struct Device<I, F: NorFlash> {
    bus: I,
    sensor: Result<Sensor, DeviceError>,
    config: SensorConfig,
    storage: Storage<F>,
    stored: bool,
    active: Calibration,
    source: ActiveCalibration,
    /// The latest capture at each face, kept for the six-position fit (indexed by `Position`).
    positions: [Option<CaptureStats>; 6],
    job: Job,
    outbox: Deque<(u16, Response), OUTBOX_LEN>,
}

impl<I, E, F> Device<I, F>
where
    I: Write<Error = E> + WriteRead<Error = E>,
    F: NorFlash,
{
    /// Boots: finds and configures the sensor, loads the stored calibration from `range` of `flash`.
    pub async fn boot(bus: I, flash: F, range: Range<u32>) -> Result<Self, StorageError> {
        let mut storage = Storage::new(flash, range)?;
        let loaded = storage.load().await;
        let config = SensorConfig::default();
        let mut device = Device {
            bus,
            sensor: Err(DeviceError::SensorMissing),
            config,
            storage,
            stored: matches!(loaded, Ok(Some(_))),
            active: Calibration::identity(config.range),
            source: ActiveCalibration::None,
            positions: [None; 6],
            job: Job::Idle,
            outbox: Deque::new(),
        };
        if let Ok(Some(calibration)) = loaded {
            device.active = calibration;
            device.source = ActiveCalibration::Stored;
        }
        let _ = device.sensor();
        Ok(device)
    }

    /// The I2C bus (the simulated sensor, in tests).
    pub fn bus_mut(&mut self) -> &mut I {
        &mut self.bus
    }

    /// The calibration applied to samples now.
    pub fn active_calibration(&self) -> Option<Calibration> {
        (self.source != ActiveCalibration::None).then_some(self.active)
    }

    /// Whether a capture or a stream is running.
    pub fn is_busy(&self) -> bool {
        self.job != Job::Idle
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

    /// Carries out one request; its final response, or the start of a long operation.
    pub async fn handle(&mut self, request_id: u16, request: Request) {
        // `Ok(None)`: a long operation started, and `poll` or `Cancel` sends its final response.
        let answer = match request {
            Request::Capture { .. } | Request::Stream { .. } if self.is_busy() => Err(DeviceError::Busy),
            Request::Capture { seconds } => self.start_capture(request_id, seconds).map(|()| None),
            Request::Stream { kind, rate_hz, count } => {
                self.start_stream(request_id, kind, rate_hz, count).map(|()| None)
            }
            request => self.answer(request).await.map(Some),
        };
        match answer {
            Ok(None) => {}
            Ok(Some(response)) => self.send(request_id, response),
            Err(error) => self.send(request_id, Response::Error(error)),
        }
    }

    /// The final response to a request that completes at once.
    async fn answer(&mut self, request: Request) -> Result<Response, DeviceError> {
        match request {
            Request::Hello { protocol_version } => Ok(self.hello(protocol_version)),
            Request::Cancel => Ok(self.cancel()),
            Request::GetCalibration(slot) => self.get_calibration(slot).await,
            _ if self.is_busy() => Err(DeviceError::Busy),
            Request::Configure(config) => self.configure(config),
            Request::ClearPositions => {
                self.positions = [None; 6];
                Ok(Response::Done)
            }
            Request::FitSixPosition => self.fit_six_position(),
            Request::SetCalibration(calibration) => self.set_calibration(calibration),
            Request::SaveCalibration => self.save().await,
            Request::EraseCalibration => self.erase().await,
            // NOTE: `handle` starts these itself; listed so that a new request cannot be forgotten.
            Request::Capture { .. } | Request::Stream { .. } => Err(DeviceError::Busy),
        }
    }

    /// Moves the running capture or stream on with whatever the FIFO holds. Call every few ms.
    pub fn poll(&mut self) {
        match self.job {
            Job::Idle => {}
            Job::Capturing { .. } => self.poll_capture(),
            Job::Streaming { .. } => self.poll_stream(),
        }
    }

    fn send(&mut self, request_id: u16, response: Response) {
        // NOTE: the outbox is drained after every request and poll, and polls take no more samples
        // than it has room for; a full outbox would only drop this message, never block.
        let _ = self.outbox.push_back((request_id, response));
    }

    /// The sensor, found again if it was missing (a loose wire put back).
    fn sensor(&mut self) -> Result<&mut Sensor, DeviceError> {
        if self.sensor.is_err() {
            self.sensor = Sensor::probe(&mut self.bus).map_err(|e| e.to_device_error()).and_then(|mut sensor| {
                sensor.configure(&mut self.bus, self.config).map_err(|e| e.to_device_error())?;
                Ok(sensor)
            });
        }
        self.sensor.as_mut().map_err(|e| *e)
    }

    /// Records a bus failure and looks for the sensor again at once: a sensor that no longer answers
    /// is reported as missing, a passing fault as the bus error it was.
    fn sensor_failed(&mut self, error: sensor::Error<E>) -> DeviceError {
        let error = error.to_device_error();
        if error == DeviceError::Bus {
            self.sensor = Err(DeviceError::Bus);
            if let Err(missing) = self.sensor() {
                return missing;
            }
        }
        error
    }

    /// Runs one driver operation on the sensor (found again first if it was missing).
    fn with_sensor<R>(
        &mut self,
        operation: impl FnOnce(&mut Sensor, &mut I) -> Result<R, sensor::Error<E>>,
    ) -> Result<R, DeviceError> {
        self.sensor()?;
        let result = match self.sensor.as_mut() {
            Ok(sensor) => operation(sensor, &mut self.bus),
            Err(error) => return Err(*error),
        };
        result.map_err(|e| self.sensor_failed(e))
    }

    fn hello(&mut self, host_version: u8) -> Response {
        if host_version != PROTOCOL_VERSION {
            return Response::Error(DeviceError::UnsupportedVersion { device: PROTOCOL_VERSION, host: host_version });
        }
        let sensor = self.sensor().map(|s| s.identity());
        let mut positions = PositionSet::default();
        for position in Position::ALL.into_iter().filter(|p| self.positions[p.index()].is_some()) {
            positions.insert(position);
        }
        Response::Hello(DeviceInfo {
            protocol_version: PROTOCOL_VERSION,
            firmware: FIRMWARE_VERSION,
            sensor,
            config: self.config,
            active: self.source,
            stored: self.stored,
            positions,
        })
    }

    fn configure(&mut self, config: SensorConfig) -> Result<Response, DeviceError> {
        let achieved = self.with_sensor(|sensor, bus| sensor.configure(bus, config))?;
        if achieved.range != self.config.range {
            // Captures belong to the range they were taken at.
            self.positions = [None; 6];
        }
        self.config = achieved;
        Ok(Response::Configured(achieved))
    }

    fn start_capture(&mut self, request_id: u16, seconds: u8) -> Result<(), DeviceError> {
        let capture = Capture::new(seconds, self.config)?;
        self.with_sensor(|sensor, bus| sensor.start_fifo(bus))?;
        let next_progress = u32::from(self.config.sample_rate_hz);
        self.job = Job::Capturing { request_id, capture, next_progress };
        Ok(())
    }

    fn poll_capture(&mut self) {
        let Job::Capturing { request_id, mut capture, mut next_progress } = self.job else {
            return;
        };
        let mut batch = [RawSample::default(); READ_BATCH];
        loop {
            match self.read_fifo(&mut batch) {
                Ok(0) => break,
                Ok(n) => {
                    capture.take(&batch[..n]);
                }
                Err(error) => return self.end_job(request_id, Response::Error(error)),
            }
            if capture.samples() >= next_progress && !capture.is_complete() {
                self.send(request_id, Response::Progress(capture.progress()));
                next_progress += u32::from(self.config.sample_rate_hz);
            }
            if capture.is_complete() {
                let response = match capture.finish() {
                    Ok(stats) => self.keep(stats),
                    Err(error) => Response::Error(error),
                };
                return self.end_job(request_id, response);
            }
        }
        self.job = Job::Capturing { request_id, capture, next_progress };
    }

    /// Keeps a finished capture for the six-position fit when it was taken at a face.
    fn keep(&mut self, stats: CaptureStats) -> Response {
        let position = Position::detect(stats.mean_g, DEFAULT_FACE_TOLERANCE_DEG).ok().map(|(p, _)| p);
        if let Some(p) = position {
            self.positions[p.index()] = Some(stats);
        }
        Response::Captured { stats, position }
    }

    fn read_fifo(&mut self, batch: &mut [RawSample]) -> Result<usize, DeviceError> {
        self.with_sensor(|sensor, bus| sensor.read_fifo(bus, batch))
    }

    fn end_job(&mut self, request_id: u16, response: Response) {
        self.job = Job::Idle;
        let bus = &mut self.bus;
        if let Ok(sensor) = self.sensor.as_mut() {
            let _ = sensor.stop_fifo(bus);
        }
        self.send(request_id, response);
    }

    fn cancel(&mut self) -> Response {
        match self.job {
            Job::Idle => {}
            Job::Capturing { request_id, .. } => self.end_job(request_id, Response::Error(DeviceError::Cancelled)),
            Job::Streaming { request_id, sent, .. } => {
                self.end_job(request_id, Response::StreamEnded { samples: sent })
            }
        }
        Response::Done
    }

    fn fit_six_position(&mut self) -> Result<Response, DeviceError> {
        let mut readings = PositionReadings::<f32>::new();
        let (mut gyro_bias, mut temp_c) = ([0.0f32; 3], 0.0f32);
        for position in Position::ALL {
            let kept = self.positions[position.index()]
                .ok_or(DeviceError::SixPosition(shared::SixPositionError::Missing(position)))?;
            readings.replace(position, kept.mean_g);
            gyro_bias = shared::linalg::add(gyro_bias, shared::linalg::scale(kept.gyro_mean_dps, 1.0 / 6.0));
            temp_c += kept.temp_c / 6.0;
        }
        let fit = readings.fit(1.0).map_err(DeviceError::SixPosition)?;
        let mut calibration = Calibration {
            matrix: fit.matrix,
            offset_g: fit.offset,
            gyro_bias_dps: gyro_bias,
            model: Model::SixPosition,
            range: self.config.range,
            temp_c,
            residual_mg: 0.0,
        };
        calibration.residual_mg = six_position_residual_mg(&calibration, &readings);
        calibration.validate().map_err(DeviceError::InvalidCalibration)?;
        self.active = calibration;
        self.source = ActiveCalibration::Unsaved;
        Ok(Response::Fitted(calibration))
    }

    fn set_calibration(&mut self, calibration: Calibration) -> Result<Response, DeviceError> {
        calibration.validate().map_err(DeviceError::InvalidCalibration)?;
        if calibration.range != self.config.range {
            return Err(DeviceError::RangeMismatch { calibration: calibration.range, configured: self.config.range });
        }
        self.active = calibration;
        self.source = ActiveCalibration::Unsaved;
        Ok(Response::Done)
    }

    async fn get_calibration(&mut self, slot: CalibrationSlot) -> Result<Response, DeviceError> {
        match slot {
            CalibrationSlot::Active => Ok(Response::Calibration(self.active_calibration())),
            CalibrationSlot::Stored if self.is_busy() => Err(DeviceError::Busy),
            CalibrationSlot::Stored => {
                self.storage.load().await.map(Response::Calibration).map_err(|_| DeviceError::Storage)
            }
        }
    }

    async fn save(&mut self) -> Result<Response, DeviceError> {
        let calibration = self.active_calibration().ok_or(DeviceError::NoCalibration)?;
        self.storage.save(&calibration).await.map_err(|_| DeviceError::Storage)?;
        self.stored = true;
        self.source = ActiveCalibration::Stored;
        Ok(Response::Done)
    }

    async fn erase(&mut self) -> Result<Response, DeviceError> {
        self.storage.erase().await.map_err(|_| DeviceError::Storage)?;
        self.stored = false;
        self.active = Calibration::identity(self.config.range);
        self.source = ActiveCalibration::None;
        Ok(Response::Done)
    }

    fn start_stream(&mut self, request_id: u16, kind: StreamKind, rate_hz: u16, count: u32) -> Result<(), DeviceError> {
        let sample_rate = self.config.sample_rate_hz;
        if rate_hz == 0 || rate_hz > sample_rate || !sample_rate.is_multiple_of(rate_hz) {
            return Err(DeviceError::InvalidRate { rate_hz });
        }
        if kind == StreamKind::Calibrated
            && self.source != ActiveCalibration::None
            && self.active.range != self.config.range
        {
            return Err(DeviceError::RangeMismatch { calibration: self.active.range, configured: self.config.range });
        }
        self.with_sensor(|sensor, bus| sensor.start_fifo(bus))?;
        let decimation = u32::from(sample_rate / rate_hz);
        let remaining = (count > 0).then_some(count);
        self.job = Job::Streaming { request_id, kind, decimation, remaining, sent: 0, skip: 0 };
        Ok(())
    }

    fn poll_stream(&mut self) {
        let Job::Streaming { request_id, kind, decimation, mut remaining, mut sent, mut skip } = self.job else {
            return;
        };
        let room = OUTBOX_LEN - self.outbox.len();
        let mut batch = [RawSample::default(); READ_BATCH];
        // NOTE: never read more samples than the outbox can send; the rest waits in the FIFO.
        let readable = (room.saturating_sub(1) * decimation as usize).min(READ_BATCH);
        let n = match self.read_fifo(&mut batch[..readable]) {
            Ok(n) => n,
            Err(error) => return self.end_job(request_id, Response::Error(error)),
        };
        for raw in &batch[..n] {
            if skip > 0 {
                skip -= 1;
                continue;
            }
            skip = decimation - 1;
            let calibration = (kind == StreamKind::Calibrated).then(|| self.active_calibration()).flatten();
            self.send(request_id, Response::Sample(sample_message(raw, sent, self.config, calibration.as_ref())));
            sent += 1;
            if let Some(left) = remaining.as_mut() {
                *left -= 1;
                if *left == 0 {
                    return self.end_job(request_id, Response::StreamEnded { samples: sent });
                }
            }
        }
        self.job = Job::Streaming { request_id, kind, decimation, remaining, sent, skip };
    }
}

/// The one place a sensor reading becomes a wire message: counts to g, deg/s and degC, corrected
/// with the calibration when one is given.
pub fn sample_message(raw: &RawSample, index: u32, config: SensorConfig, calibration: Option<&Calibration>) -> Sample {
    let lsb = config.range.lsb_per_g();
    let accel_g = raw.accel.map(|a| f32::from(a) / lsb);
    let gyro_dps = raw.gyro.map(|g| f32::from(g) / crate::sensor::registers::GYRO_LSB_PER_DPS);
    let (accel_g, gyro_dps) = match calibration {
        Some(c) => (c.apply(accel_g), c.apply_gyro(gyro_dps)),
        None => (accel_g, gyro_dps),
    };
    Sample { index, accel_g, gyro_dps, temp_c: raw.temp_c() }
}

/// RMS over the six faces of |M (m - o) - face| in mg: what the placement and noise leave.
fn six_position_residual_mg(calibration: &Calibration, readings: &PositionReadings<f32>) -> f32 {
    let mut sum = 0.0;
    for position in Position::ALL {
        if let Some(reading) = readings.get(position) {
            let error = shared::linalg::sub(calibration.apply(reading), position.specific_force_g());
            sum += shared::linalg::dot(error, error);
        }
    }
    libm::sqrtf(sum / 6.0) * 1000.0
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
