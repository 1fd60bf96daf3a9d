//! What an export starts from: a calibration record (from any JSON accelcal writes, or the board), the
//! board it belongs to when that is known, and the noise terms for Kalibr.

use shared::linalg::{self, Vec3};
use shared::protocol::SensorConfig;
use shared::{AccelRange, Calibration};

use super::loss::Carried;
use super::ExportError;
use crate::calibration::{self, CalibrationJson};
use crate::noise;
use crate::session::{OutcomeError, Session};

/// A calibration to export and where it came from.
#[derive(Debug, Clone)]
pub struct Source {
    /// The calibration record, as the chip holds it (f32).
    pub calibration: Calibration,
    /// The board's serial number, when what was read records it.
    pub serial: Option<String>,
    /// Where the calibration was read from (a file's path, or the board's port).
    pub from: String,
    /// Kalibr's noise terms, when a noise report was given.
    pub noise: Option<Noise>,
}

/// Kalibr's four continuous-time noise terms and the sample rate, from `accelcal noise --json`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Noise {
    /// Accelerometer white noise, m/s^2/sqrt(Hz) (two-sided, Kalibr's convention).
    pub accel_noise_density: f64,
    /// Accelerometer bias random walk, m/s^3/sqrt(Hz).
    pub accel_random_walk: f64,
    /// Gyro white noise, rad/s/sqrt(Hz).
    pub gyro_noise_density: f64,
    /// Gyro bias random walk, rad/s^2/sqrt(Hz).
    pub gyro_random_walk: f64,
    /// The recording's sample rate, Hz.
    pub rate_hz: f64,
}

impl Source {
    /// Reads what `calibrate --json`, `fit --json` (in g), `download` or a session file holds.
    pub fn from_text(text: &str, from: &str) -> Result<Self, ExportError> {
        let value: serde_json::Value =
            serde_json::from_str(text).map_err(|e| ExportError::NotJson { reason: e.to_string() })?;
        let is_session = value.get("captures").is_some_and(serde_json::Value::is_array);
        if is_session && value.get("calibration").is_none() {
            let session: Session =
                serde_json::from_value(value).map_err(|e| ExportError::NotJson { reason: e.to_string() })?;
            return Self::from_session(&session, from);
        }
        let record = CalibrationJson::from_text(text)?;
        let calibration = record.to_device(AccelRange::default())?;
        Ok(Source { calibration, serial: None, from: from.to_owned(), noise: None })
    }

    /// The calibration a session's captures give, fitted as `calibrate` fitted it (the gyro's G, which
    /// needs the moves between positions, is not in a session file).
    pub fn from_session(session: &Session, from: &str) -> Result<Self, ExportError> {
        let config = session.board.as_ref().map_or_else(SensorConfig::default, |b| b.config);
        let calibration = match session.outcome(config) {
            Ok(outcome) => outcome.calibration,
            Err(OutcomeError::Fit(e)) => return Err(ExportError::Fit(e)),
            Err(OutcomeError::Calibration(e)) => return Err(e.into()),
        };
        let serial = session.board.as_ref().map(|b| b.serial.clone());
        Ok(Source { calibration, serial, from: from.to_owned(), noise: None })
    }

    /// The full calibration in f64 (the record's f32 values widened), as the loss's reference.
    pub fn full(&self) -> Carried {
        let (matrix, offset_g) = calibration::static_part(&self.calibration);
        let gyro = &self.calibration.gyro;
        Carried {
            matrix,
            offset_g,
            gyro_matrix: gyro.matrix.map(|row| row.map(f64::from)),
            gyro_bias_dps: Some(gyro.bias_dps.map(f64::from)),
        }
    }

    /// Raw counts per g of the calibration's range.
    pub fn lsb_per_g(&self) -> f64 {
        f64::from(self.calibration.range.lsb_per_g())
    }

    /// The gyro bias in deg/s.
    pub fn gyro_bias_dps(&self) -> Vec3<f64> {
        self.calibration.gyro.bias_dps.map(f64::from)
    }

    /// Whether the gyro's G was fitted (is not the identity).
    pub fn has_gyro_matrix(&self) -> bool {
        self.calibration.gyro.matrix != linalg::identity::<f32>()
    }
}

impl Noise {
    /// Kalibr's numbers from `accelcal noise --json` (its `kalibr.continuous_time` and `sample_rate_hz`).
    pub fn from_text(text: &str) -> Result<Self, ExportError> {
        let report = noise::json::read(text).map_err(|reason| ExportError::NoiseFile { reason })?;
        let lacks = |name: &str| ExportError::NoiseFile {
            reason: format!("no {name}: give the output of `accelcal noise RECORDING --json`"),
        };
        let terms = report.kalibr.ok_or_else(|| lacks("kalibr"))?.continuous_time;
        Ok(Noise {
            accel_noise_density: terms.accelerometer_noise_density,
            accel_random_walk: terms.accelerometer_random_walk,
            gyro_noise_density: terms.gyroscope_noise_density,
            gyro_random_walk: terms.gyroscope_random_walk,
            rate_hz: report.sample_rate_hz.ok_or_else(|| lacks("sample_rate_hz"))?,
        })
    }
}
