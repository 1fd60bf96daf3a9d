//! Routing: every request to the operation that answers it, exactly one final response each.

use embedded_hal::blocking::i2c::{Write, WriteRead};
use embedded_storage_async::nor_flash::NorFlash;
use shared::protocol::{DeviceError, DeviceInfo, Request, Response, SensorConfig, PROTOCOL_VERSION};
use shared::PositionMap;

use super::{Device, FIRMWARE_VERSION};

impl<I, E, F> Device<I, F>
where
    I: Write<Error = E> + WriteRead<Error = E>,
    F: NorFlash,
{
    /// Carries out one request; its final response, or the start of a long operation.
    pub async fn handle(&mut self, request_id: u16, request: Request) {
        // `Ok(None)`: a long operation started, and `poll` or `Cancel` sends its final response.
        let answer = match request {
            Request::Capture { .. } | Request::Stream { .. } | Request::CaptureUntil(_) if self.is_busy() => {
                Err(DeviceError::Busy)
            }
            Request::Capture { seconds } => self.start_capture(request_id, seconds).map(|()| None),
            Request::CaptureUntil(goal) => self.start_capture_until(request_id, goal).map(|()| None),
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
            Request::TakeTemperatureBins => {
                Ok(Response::TemperatureBins(self.temperature_bins.take(self.config.range)))
            }
            _ if self.is_busy() => Err(DeviceError::Busy),
            Request::Configure(config) => self.configure(config),
            Request::ClearPositions => {
                self.positions.clear();
                self.kept.clear();
                Ok(Response::Done)
            }
            Request::FitSixPosition => self.fit_six_position(),
            Request::SetCalibration(calibration) => self.set_calibration(calibration),
            Request::SaveCalibration => self.save().await,
            Request::EraseCalibration => self.erase().await,
            Request::FitOrtho9 => self.fit_ortho9(),
            // NOTE: `handle` starts these itself; listed so that a new request cannot be forgotten.
            Request::Capture { .. } | Request::Stream { .. } | Request::CaptureUntil(_) => Err(DeviceError::Busy),
        }
    }

    fn hello(&mut self, host_version: u8) -> Response {
        if host_version != PROTOCOL_VERSION {
            return Response::Error(DeviceError::UnsupportedVersion { device: PROTOCOL_VERSION, host: host_version });
        }
        if !self.is_busy() {
            // NOTE: a sensor found earlier may have come loose since: look again, so hello tells
            // the truth (never mid-capture or mid-stream, where the FIFO is in use).
            self.sensor = Err(DeviceError::SensorMissing);
        }
        let sensor = self.sensor().map(|s| s.identity());
        Response::Hello(DeviceInfo {
            protocol_version: PROTOCOL_VERSION,
            serial: self.serial,
            firmware: FIRMWARE_VERSION,
            sensor,
            config: self.config,
            active: self.source,
            stored: self.stored,
            positions: self.positions.marks(),
        })
    }

    fn configure(&mut self, config: SensorConfig) -> Result<Response, DeviceError> {
        let achieved = self.with_sensor(|sensor, bus| sensor.configure(bus, config))?;
        if achieved.range != self.config.range {
            // Captures and bins belong to the range they were taken at.
            self.positions = PositionMap::new();
            self.temperature_bins.clear();
            self.kept.clear();
        }
        self.config = achieved;
        Ok(Response::Configured(achieved))
    }
}
