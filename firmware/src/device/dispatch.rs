//! Routing: every request to the operation that answers it, exactly one final response each.

use embedded_hal_async::i2c::I2c;
use embedded_storage_async::nor_flash::NorFlash;
use shared::protocol::{DeviceError, DeviceInfo, Request, Response, SensorConfig, PROTOCOL_VERSION};
use shared::PositionMap;

use super::{Device, SensorOp, FIRMWARE_VERSION};

impl<I, F> Device<I, F>
where
    I: I2c,
    F: NorFlash,
{
    /// Carries out one request; its final response, or the start of a long operation.
    pub async fn handle(&mut self, request_id: u16, request: Request) {
        // `Ok(None)`: a long operation started, and `poll` or `Cancel` sends its final response.
        let answer = match request {
            Request::Capture { .. } | Request::Stream { .. } | Request::CaptureUntil(_) if self.is_busy() => {
                Err(DeviceError::Busy)
            }
            Request::Capture { seconds } => self.start_capture(request_id, seconds).await.map(|()| None),
            Request::CaptureUntil(goal) => self.start_capture_until(request_id, goal).await.map(|()| None),
            Request::Stream { kind, rate_hz, count } => {
                self.start_stream(request_id, kind, rate_hz, count).await.map(|()| None)
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
            Request::Hello { protocol_version } => Ok(self.hello(protocol_version).await),
            Request::Cancel => Ok(self.cancel().await),
            Request::GetCalibration(slot) => self.get_calibration(slot).await,
            Request::TakeTemperatureBins => {
                Ok(Response::TemperatureBins(self.temperature_bins.take(self.config.range)))
            }
            _ if self.is_busy() => Err(DeviceError::Busy),
            request @ (Request::Configure(_) | Request::Register { .. }) => self.sensor_request(request).await,
            Request::ClearPositions => {
                self.positions.clear();
                self.kept.clear();
                Ok(Response::Done)
            }
            Request::FitSixPosition => self.fit_six_position(),
            Request::SetCalibration(calibration) => self.set_calibration(calibration),
            request @ (Request::SaveCalibration | Request::EraseCalibration | Request::StoreSelfTest(_)) => {
                self.storage_request(request).await
            }
            Request::FitOrtho9 => self.fit_ortho9(),
            // NOTE: `handle` starts these itself; listed so that a new request cannot be forgotten.
            Request::Capture { .. } | Request::Stream { .. } | Request::CaptureUntil(_) => Err(DeviceError::Busy),
        }
    }

    async fn hello(&mut self, host_version: u8) -> Response {
        if host_version != PROTOCOL_VERSION {
            return Response::Error(DeviceError::UnsupportedVersion { device: PROTOCOL_VERSION, host: host_version });
        }
        if !self.is_busy() {
            // NOTE: a sensor found earlier may have come loose since: look again, so hello tells
            // the truth (never mid-capture or mid-stream, where the FIFO is in use).
            self.sensor = Err(DeviceError::SensorMissing);
        }
        let sensor = self.sensor().await.map(|s| s.identity());
        Response::Hello(DeviceInfo {
            protocol_version: PROTOCOL_VERSION,
            serial: self.serial,
            firmware: FIRMWARE_VERSION,
            sensor,
            config: self.config,
            active: self.source,
            stored: self.stored,
            positions: self.positions.marks(),
            self_test: self.self_test.clone(),
        })
    }

    /// The requests that are one driver operation: configure, and a register's write and read.
    ///
    /// NOTE: one await for both: every await in the request path costs flash.
    async fn sensor_request(&mut self, request: Request) -> Result<Response, DeviceError> {
        let operation = match request {
            Request::Register { register, write } => SensorOp::Register(register, write),
            Request::Configure(config) => SensorOp::Configure(config),
            _ => return Err(DeviceError::Busy),
        };
        let value = self.with_sensor(operation).await?;
        Ok(match request {
            Request::Configure(config) => self.configured(config),
            _ => Response::Register(value as u8),
        })
    }

    /// The device's configuration after the sensor was configured for `config`.
    fn configured(&mut self, config: SensorConfig) -> Response {
        let achieved = self.sensor.map_or(config, |sensor| sensor.config());
        if achieved.range != self.config.range {
            // Captures and bins belong to the range they were taken at.
            self.positions = PositionMap::new();
            self.temperature_bins.clear();
            self.kept.clear();
        }
        self.config = achieved;
        Response::Configured(achieved)
    }
}
