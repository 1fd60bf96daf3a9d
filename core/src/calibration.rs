//! The device's calibration record on the host, in one place: its JSON form (which `download`,
//! `fit --json` and `calibrate --json` write and `upload` reads), the record made from a host fit,
//! and its one-line description. No other host code reads or writes `shared::Calibration` fields.

mod reason;

pub use reason::calibration_reason;

use serde::{Deserialize, Serialize};
use shared::calibration::{GyroCalibration, ModelTag, Origin, Procedure, TemperatureModel, MODEL_TAG_LEN};
use shared::linalg;
use shared::protocol::{LowPassFilter, SensorConfig};
use shared::{AccelRange, Calibration, CalibrationError};

use crate::data::Dataset;
use crate::fit::gyro::GyroFit;
use crate::fit::thermal::ThermalReference;
use crate::fit::{self, Fit};
use crate::shown::shown;

/// A calibration as JSON, under the convention a = matrix (m - offset).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CalibrationJson {
    /// The model that made it (`six-position`, `ortho9`, ...).
    pub model: String,
    /// M, 3 rows, dimensionless.
    pub matrix: [[f64; 3]; 3],
    /// o, in g for a device calibration, in the data file's unit for a fit.
    pub offset: [f64; 3],
    /// |gravity| in the unit of `offset`; absent means g (a device calibration).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub g: Option<f64>,
    /// Which procedure made it (`chip-fit`, `host-fit`, `uploaded`); absent for a fit of a data file.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub procedure: Option<Procedure>,
    /// Gyro bias in deg/s; absent for a fit of accelerometer data alone.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gyro_bias_dps: Option<[f64; 3]>,
    /// Gyro scale and misalignment matrix G, 3 rows; absent means identity.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gyro_matrix: Option<[[f64; 3]; 3]>,
    /// The accelerometer range it belongs to, full scale in g.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub range_g: Option<u8>,
    /// The low-pass filter it belongs to (`Hz44`, ...); absent means the default, 44 Hz.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub filter: Option<LowPassFilter>,
    /// Mean die temperature of the captures it was fitted from, in degC (`temp_c` in older files).
    #[serde(default, alias = "temp_c", skip_serializing_if = "Option::is_none")]
    pub mean_temp_c: Option<f64>,
    /// How offset, scale and gyro bias change with temperature (DESIGN.md); absent: they do not.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub temperature: Option<TemperatureModel>,
    /// RMS fit residual, in mg.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub residual_mg: Option<f64>,
}

/// Why a calibration was refused before it reached the device.
#[derive(Debug, thiserror::Error)]
pub enum CalibrationRecordError {
    #[error("not a JSON calibration: {reason}; give the output of download, fit --json or calibrate --json")]
    NotJson { reason: String },
    #[error("no calibration in the file ({reason}); give the output of download, fit --json or calibrate --json")]
    NotACalibration { reason: String },
    #[error("this fit is not in g: fit data in g with --g 1 before uploading")]
    NotInG { g: f64 },
    #[error("refused before upload: {}", calibration_reason(.0))]
    Implausible(CalibrationError),
    #[error("the {model} fit is implausible: {}; capture the positions again, holding the board still", calibration_reason(.reason))]
    ImplausibleFit { model: &'static str, reason: CalibrationError },
}

impl CalibrationJson {
    /// The JSON form of a device calibration (in g). NOTE: every f32 is exactly an f64, so the
    /// calibration read back is bit for bit the one written.
    pub fn from_device(calibration: &Calibration) -> Self {
        CalibrationJson {
            model: calibration.origin.model.as_str().to_owned(),
            matrix: widen(calibration.matrix),
            offset: calibration.offset_g.map(f64::from),
            g: None,
            procedure: Some(calibration.origin.procedure),
            gyro_bias_dps: Some(calibration.gyro.bias_dps.map(f64::from)),
            gyro_matrix: Some(widen(calibration.gyro.matrix)),
            range_g: Some(calibration.range.full_scale_g()),
            filter: Some(calibration.filter),
            mean_temp_c: Some(f64::from(calibration.mean_temp_c)),
            temperature: calibration.temperature,
            residual_mg: Some(f64::from(calibration.residual_mg)),
        }
    }

    /// The JSON form of a fit, in the data file's unit with |gravity| `g`.
    pub fn from_fit(fit: &Fit, g: f64) -> Self {
        CalibrationJson {
            model: fit.model.name().to_owned(),
            matrix: fit.matrix,
            offset: fit.offset,
            g: Some(g),
            procedure: None,
            gyro_bias_dps: None,
            gyro_matrix: None,
            range_g: None,
            filter: None,
            mean_temp_c: None,
            temperature: None,
            residual_mg: None,
        }
    }

    /// Reads what `download`, `fit --json` (on data in g) or `calibrate --json` wrote.
    pub fn from_text(text: &str) -> Result<Self, CalibrationRecordError> {
        let value: serde_json::Value =
            serde_json::from_str(text).map_err(|e| CalibrationRecordError::NotJson { reason: e.to_string() })?;
        // `calibrate --json` holds the calibration under "calibration"; the others are one.
        let record = value.get("calibration").cloned().unwrap_or(value);
        serde_json::from_value(record).map_err(|e| CalibrationRecordError::NotACalibration { reason: e.to_string() })
    }

    /// The device calibration, for the device's `range` unless the JSON names one; refuses a fit
    /// not in g and an implausible calibration.
    pub fn to_device(&self, range: AccelRange) -> Result<Calibration, CalibrationRecordError> {
        if let Some(g) = self.g.filter(|g| (g - 1.0).abs() > 1e-12) {
            return Err(CalibrationRecordError::NotInG { g });
        }
        let identity = Calibration::identity(range);
        let calibration = Calibration {
            origin: self.origin(),
            range: self.range_g.and_then(AccelRange::from_full_scale_g).unwrap_or(range),
            filter: self.filter.unwrap_or_default(),
            matrix: narrow(self.matrix),
            offset_g: self.offset.map(|v| v as f32),
            gyro: GyroCalibration {
                matrix: self.gyro_matrix.map_or(identity.gyro.matrix, narrow),
                bias_dps: self.gyro_bias_dps.unwrap_or_default().map(|v| v as f32),
            },
            mean_temp_c: self.mean_temp_c.unwrap_or(0.0) as f32,
            temperature: self.temperature,
            residual_mg: self.residual_mg.unwrap_or(0.0) as f32,
        };
        calibration.validate().map_err(CalibrationRecordError::Implausible)?;
        Ok(calibration)
    }
}

impl CalibrationJson {
    /// Where the record came from: as written by a device, else uploaded with the model's name as its
    /// tag (cut to the tag's length, so a long name from another tool still loads).
    fn origin(&self) -> Origin {
        let tag = (0..=self.model.len().min(MODEL_TAG_LEN))
            .rev()
            .find_map(|len| self.model.get(..len).and_then(ModelTag::new))
            .unwrap_or_default();
        Origin { procedure: self.procedure.unwrap_or(Procedure::Uploaded), model: tag }
    }
}

fn widen(matrix: [[f32; 3]; 3]) -> [[f64; 3]; 3] {
    matrix.map(|row| row.map(f64::from))
}

fn narrow(matrix: [[f64; 3]; 3]) -> [[f32; 3]; 3] {
    matrix.map(|row| row.map(|v| v as f32))
}

/// `calibration` with an offset drift of `slope_g_per_c` (g/degC) about `ref_c` degC, measured
/// within one session: the chip then moves the offset with the die temperature.
pub fn with_offset_drift(calibration: &Calibration, ref_c: f64, slope_g_per_c: [f64; 3]) -> Calibration {
    let mut model = shared::calibration::TemperatureModel::flat(ref_c as f32);
    model.offset_g[0] = slope_g_per_c.map(|v| v as f32);
    Calibration { temperature: Some(model), ..*calibration }
}

/// The device calibration from a host fit over a session's captures (in g, as fitted) taken with
/// `config`: the fit's M and o, the captures' mean gyro reading as the gyro bias, their mean
/// temperature, and the fit's RMS residual over them.
pub fn from_fit(fit: &Fit, captures: &Dataset, config: SensorConfig) -> Result<Calibration, CalibrationRecordError> {
    let range = config.range;
    let n = captures.rows.len().max(1) as f32;
    // NOTE: the captures' statistics are f32 on the chip: summed in f32 as before they were rows.
    let gyro_of = |r: &crate::data::Row| r.gyro_mean_dps.unwrap_or_default().map(|v| v as f32);
    let gyro_bias =
        captures.rows.iter().fold([0.0f32; 3], |sum, r| linalg::add(sum, linalg::scale(gyro_of(r), 1.0 / n)));
    let mean_temp_c = captures.rows.iter().map(|r| r.temp_c.unwrap_or_default() as f32).sum::<f32>() / n;
    let evaluation = fit::evaluate(captures, &fit.matrix, &fit.offset, 1.0, &fit.lines_used);
    let residual_mg = evaluation.rms_norm_error(true).unwrap_or(0.0) * 1000.0;
    let calibration = Calibration {
        origin: fit.model.origin(),
        range,
        filter: config.filter,
        matrix: narrow(fit.matrix),
        offset_g: fit.offset.map(|v| v as f32),
        gyro: GyroCalibration { bias_dps: gyro_bias, ..Calibration::identity(range).gyro },
        mean_temp_c,
        temperature: None,
        residual_mg: residual_mg as f32,
    };
    let implausible = |reason| CalibrationRecordError::ImplausibleFit { model: fit.model.name(), reason };
    calibration.validate().map_err(implausible)?;
    Ok(calibration)
}

/// What the chip applies at `temp_c` degC, as a = matrix (m - offset): M diag(1 + d(T))^-1 and o(T).
pub fn applied_at(calibration: &Calibration, temp_c: f32) -> ([[f64; 3]; 3], [f64; 3]) {
    let Some((offset, scale)) = calibration.accel_terms_at(temp_c) else {
        return static_part(calibration);
    };
    let matrix = calibration.matrix.map(|row| [0, 1, 2].map(|j| f64::from(row[j]) / (1.0 + f64::from(scale[j]))));
    (matrix, offset.map(f64::from))
}

/// M and o without the temperature model.
pub fn static_part(calibration: &Calibration) -> ([[f64; 3]; 3], [f64; 3]) {
    (widen(calibration.matrix), calibration.offset_g.map(f64::from))
}

/// The gyro bias b(T) the chip subtracts at `temp_c` degC, in deg/s.
pub fn gyro_bias_at(calibration: &Calibration, temp_c: f32) -> [f64; 3] {
    calibration.gyro_bias_at(temp_c).map(f64::from)
}

/// What a temperature model is fitted around: the captures' mean temperature and M.
pub fn thermal_reference(calibration: &Calibration) -> ThermalReference {
    ThermalReference { ref_temp_c: calibration.mean_temp_c, matrix: calibration.matrix }
}

/// The calibration with a fitted temperature model, checked like any other.
pub fn with_temperature(
    calibration: &Calibration,
    model: TemperatureModel,
) -> Result<Calibration, CalibrationRecordError> {
    checked(Calibration { temperature: Some(model), ..*calibration }, "temperature")
}

/// The calibration with the gyro matrix G of `fit` (w = G (w_raw - b)), checked like any other.
pub fn with_gyro(calibration: &Calibration, fit: &GyroFit) -> Result<Calibration, CalibrationRecordError> {
    let gyro = GyroCalibration { matrix: narrow(fit.matrix), ..calibration.gyro };
    checked(Calibration { gyro, ..*calibration }, "gyro")
}

/// `calibration` when it is plausible, else the `model` fit that made it named as implausible.
fn checked(calibration: Calibration, model: &'static str) -> Result<Calibration, CalibrationRecordError> {
    calibration.validate().map_err(|reason| CalibrationRecordError::ImplausibleFit { model, reason })?;
    Ok(calibration)
}

/// One line: model, scales, offset in mg, residual, and the temperature model when there is one.
pub fn describe(calibration: &Calibration) -> String {
    let m = calibration.matrix;
    let o = calibration.offset_g.map(|v| shown(f64::from(v) * 1000.0, 2));
    let temperature = calibration.temperature.map_or(String::new(), |model| {
        let slope = model.offset_g[0].map(|v| shown(f64::from(v) * 1000.0, 2));
        format!(
            "; temperature model around {:.1} degC (offset {:+.2} {:+.2} {:+.2} mg/degC)",
            model.ref_temp_c, slope[0], slope[1], slope[2]
        )
    });
    format!(
        "{}: scale {:.5} {:.5} {:.5}, offset {:+.2} {:+.2} {:+.2} mg, residual {:.3} mg{}{temperature}",
        calibration.origin.model.as_str(),
        m[0][0],
        m[1][1],
        m[2][2],
        o[0],
        o[1],
        o[2],
        calibration.residual_mg,
        gyro_text(&calibration.gyro)
    )
}

/// The gyro part of [`describe`]: G's diagonal when it is not the identity, and the bias.
fn gyro_text(gyro: &GyroCalibration) -> String {
    let g = gyro.matrix;
    let scale = (g != linalg::identity::<f32>()).then(|| format!("G {:.5} {:.5} {:.5}, ", g[0][0], g[1][1], g[2][2]));
    let [x, y, z] = gyro.bias_dps;
    format!("; gyro {}bias {x:+.3} {y:+.3} {z:+.3} deg/s", scale.unwrap_or_default())
}

#[cfg(test)]
mod tests;
