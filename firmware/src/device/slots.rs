//! The calibration slots: the active one in RAM (fitted on the chip or uploaded) and the stored one in
//! flash, each change validated first; and the latest self-test beside it in flash.

use embedded_hal_async::i2c::I2c;
use embedded_storage_async::nor_flash::NorFlash;
use shared::calibration::{GyroCalibration, Origin};
use shared::linalg::{self, Vec3};
use shared::protocol::{
    ActiveCalibration, CalibrationSlot, CaptureStats, DeviceError, Request, Response, SensorConfig,
};
use shared::{Calibration, Position, PositionMap, SixPositionError};

use super::Device;
use crate::storage::Record;

impl<I, F> Device<I, F>
where
    I: I2c,
    F: NorFlash,
{
    /// Fits the kept captures on the chip and returns the fit when it is plausible.
    ///
    /// NOTE: the fit does not become active: the host makes active only what it uploads, so a person
    /// who declines the upload leaves the board exactly as it was.
    pub(super) fn fit_six_position(&mut self) -> Result<Response, DeviceError> {
        let calibration = six_position_calibration(&self.positions, self.config)?;
        calibration.validate().map_err(DeviceError::InvalidCalibration)?;
        Ok(Response::Fitted(calibration))
    }

    pub(super) fn set_calibration(&mut self, calibration: Calibration) -> Result<Response, DeviceError> {
        calibration.validate().map_err(DeviceError::InvalidCalibration)?;
        if calibration.range != self.config.range {
            return Err(DeviceError::RangeMismatch { calibration: calibration.range, configured: self.config.range });
        }
        self.active = calibration;
        self.source = ActiveCalibration::Unsaved;
        Ok(Response::Done)
    }

    pub(super) async fn get_calibration(&mut self, slot: CalibrationSlot) -> Result<Response, DeviceError> {
        match slot {
            CalibrationSlot::Active => Ok(Response::Calibration(self.active_calibration())),
            CalibrationSlot::Stored if self.is_busy() => Err(DeviceError::Busy),
            CalibrationSlot::Stored => {
                self.storage.load().await.map(Response::Calibration).map_err(|_| DeviceError::Storage)
            }
        }
    }

    /// The requests that write flash: a calibration's save or erase, and a self-test's.
    ///
    /// NOTE: one await for the three: every await in the request path costs flash.
    pub(super) async fn storage_request(&mut self, request: Request) -> Result<Response, DeviceError> {
        let active = self.active_calibration();
        let record = match &request {
            Request::SaveCalibration => Record::Calibration(Some(active.as_ref().ok_or(DeviceError::NoCalibration)?)),
            Request::StoreSelfTest(self_test) => Record::SelfTest(self_test),
            // NOTE: `answer` routes only the three here: the last is the erase.
            _ => Record::Calibration(None),
        };
        self.storage.write(record).await.map_err(|_| DeviceError::Storage)?;
        match request {
            Request::SaveCalibration => {
                self.stored = true;
                self.source = ActiveCalibration::Stored;
            }
            Request::StoreSelfTest(self_test) => self.self_test = Some(self_test),
            _ => {
                self.stored = false;
                self.active = Calibration::identity(self.config.range);
                self.source = ActiveCalibration::None;
            }
        }
        Ok(Response::Done)
    }
}

/// The six-position closed form over the kept captures, with the gyro bias and temperature averaged
/// over them and the residual the placement and noise leave.
fn six_position_calibration(
    captures: &PositionMap<CaptureStats>,
    config: SensorConfig,
) -> Result<Calibration, DeviceError> {
    let mut readings = PositionMap::<Vec3<f32>>::new();
    let (mut gyro_bias_dps, mut mean_temp_c) = ([0.0f32; 3], 0.0f32);
    for position in Position::ALL {
        let kept = captures.get(position).ok_or(DeviceError::SixPosition(SixPositionError::Missing(position)))?;
        readings.replace(position, kept.mean_g);
        gyro_bias_dps = linalg::add(gyro_bias_dps, linalg::scale(kept.gyro_mean_dps, 1.0 / 6.0));
        mean_temp_c += kept.temp_c / 6.0;
    }
    let fit = readings.fit(1.0).map_err(DeviceError::SixPosition)?;
    let mut calibration = Calibration {
        origin: Origin::CHIP_SIX_POSITION,
        range: config.range,
        filter: config.filter,
        matrix: fit.matrix,
        offset_g: fit.offset,
        gyro: GyroCalibration { bias_dps: gyro_bias_dps, ..GyroCalibration::default() },
        mean_temp_c,
        temperature: None,
        residual_mg: 0.0,
    };
    calibration.residual_mg = six_position_residual_mg(&calibration, &readings);
    Ok(calibration)
}

/// RMS over the six faces of |M (m - o) - face| in mg: what the placement and noise leave.
fn six_position_residual_mg(calibration: &Calibration, readings: &PositionMap<Vec3<f32>>) -> f32 {
    let mut sum = 0.0;
    for position in readings.present() {
        if let Some(&reading) = readings.get(position) {
            let error = linalg::sub(calibration.apply(reading), position.specific_force_g());
            sum += linalg::dot(error, error);
        }
    }
    libm::sqrtf(sum / 6.0) * 1000.0
}
