//! The plausibility limits of a calibration, each with its reason, and the check that applies them.

use serde::{Deserialize, Serialize};

use super::temperature::{drift, TempCoefficients, TemperatureModel};
use super::Calibration;
use crate::linalg::{self, Mat3, Vec3};

/// Limits outside which a calibration is refused as absurd for an MPU-6050. The one table: error
/// messages quote these constants, never their own copies of the numbers.
///
/// NOTE: figures from the MPU-6000/6050 Product Specification rev 3.4, sections 6.1 (gyro) and 6.2
/// (accelerometer); each limit leaves a wide margin for the sensor's mounting on its board while
/// still refusing a fit that went wrong (wrong unit, swapped axes, a moved capture).
pub mod limits {
    /// Each diagonal element of M must lie in this range: the sensitivity tolerance is +-3 %, and a
    /// factor of 2 either way is a wrong range or unit, not a sensor error.
    pub const SCALE: (f32, f32) = (0.5, 2.0);
    /// Largest magnitude of an off-diagonal element of M: cross-axis sensitivity is +-2 %, and
    /// 0.25 (14 degrees of misalignment) is more than any board mounting.
    pub const CROSS_AXIS: f32 = 0.25;
    /// Smallest |det M| and |det G|; below this a matrix is treated as singular (with the scale and
    /// cross-axis limits a plausible matrix has a determinant near 1).
    pub const MIN_DETERMINANT: f32 = 0.1;
    /// Largest magnitude of an offset component, in g: the zero-g offset is at most +-80 mg on x
    /// and y and +-150 mg on z.
    pub const OFFSET_G: f32 = 0.5;
    /// Each diagonal element of G must lie in this range: the gyro sensitivity tolerance is +-3 %;
    /// a factor of 2 is a wrong full-scale setting.
    pub const GYRO_SCALE: (f32, f32) = (0.5, 2.0);
    /// Largest magnitude of an off-diagonal element of G: the gyro cross-axis sensitivity is +-2 %.
    pub const GYRO_CROSS_AXIS: f32 = 0.25;
    /// Largest magnitude of a gyro bias component, in deg/s: the zero-rate output is +-20 deg/s.
    pub const GYRO_BIAS_DPS: f32 = 50.0;
    /// The temperatures a temperature model must hold over, in degC: the operating range.
    pub const OPERATING_TEMP_C: (f32, f32) = (-40.0, 85.0);
    /// Largest offset drift of a temperature model over the operating range, in g: the zero-g
    /// level moves by +-35 mg (x, y) and +-60 mg (z) over 0-70 degC.
    pub const OFFSET_DRIFT_G: f32 = 0.5;
    /// Largest relative scale drift over the operating range: the sensitivity moves by +-0.02 %/degC,
    /// 2.5 % over the range; 0.5 keeps the divisor 1 + drift far from zero.
    pub const SCALE_DRIFT: f32 = 0.5;
    /// Largest gyro bias drift over the operating range, in deg/s: the zero-rate output moves by
    /// +-20 deg/s over -40 to +85 degC.
    pub const GYRO_BIAS_DRIFT_DPS: f32 = 50.0;
}

/// Temperatures, as steps across [`limits::OPERATING_TEMP_C`], at which a drift is checked.
const DRIFT_CHECK_STEPS: u8 = 8;

/// Why a calibration was refused.
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq)]
pub enum CalibrationError {
    /// A value is NaN or infinite.
    NonFinite,
    /// |det M| is below the limit: M cannot be a correction.
    Singular { determinant: f32 },
    /// A diagonal element of M (the scale of `axis`, 0 = x) is outside the allowed range.
    ScaleOutOfRange { axis: u8, value: f32 },
    /// An off-diagonal element M[row][col] is larger than the allowed cross-axis term.
    CrossAxisOutOfRange { row: u8, col: u8, value: f32 },
    /// An offset component in g is larger than the allowed limit.
    OffsetOutOfRange { axis: u8, value_g: f32 },
    /// A gyro bias component in deg/s is larger than the allowed limit.
    GyroBiasOutOfRange { axis: u8, value_dps: f32 },
    /// |det G| is below the limit: G cannot be a correction.
    GyroSingular { determinant: f32 },
    /// A diagonal element of G is outside the allowed range.
    GyroScaleOutOfRange { axis: u8, value: f32 },
    /// An off-diagonal element G[row][col] is larger than the allowed cross-axis term.
    GyroCrossAxisOutOfRange { row: u8, col: u8, value: f32 },
    /// The temperature model's T_ref, in degC, lies outside the operating range.
    ReferenceTemperatureOutOfRange { value_c: f32 },
    /// The offset of `axis` drifts by more than the limit, in g, somewhere in the operating range.
    OffsetDriftOutOfRange { axis: u8, value_g: f32 },
    /// The scale of `axis` drifts by more than the limit somewhere in the operating range.
    ScaleDriftOutOfRange { axis: u8, value: f32 },
    /// The gyro bias of `axis` drifts by more than the limit, in deg/s, in the operating range.
    GyroBiasDriftOutOfRange { axis: u8, value_dps: f32 },
}

/// The limits of one correction matrix, and the errors that name a breach of them.
struct MatrixLimits {
    scale: (f32, f32),
    cross_axis: f32,
    singular: fn(f32) -> CalibrationError,
    scale_error: fn(u8, f32) -> CalibrationError,
    cross_error: fn(u8, u8, f32) -> CalibrationError,
}

const ACCEL_MATRIX: MatrixLimits = MatrixLimits {
    scale: limits::SCALE,
    cross_axis: limits::CROSS_AXIS,
    singular: |determinant| CalibrationError::Singular { determinant },
    scale_error: |axis, value| CalibrationError::ScaleOutOfRange { axis, value },
    cross_error: |row, col, value| CalibrationError::CrossAxisOutOfRange { row, col, value },
};

const GYRO_MATRIX: MatrixLimits = MatrixLimits {
    scale: limits::GYRO_SCALE,
    cross_axis: limits::GYRO_CROSS_AXIS,
    singular: |determinant| CalibrationError::GyroSingular { determinant },
    scale_error: |axis, value| CalibrationError::GyroScaleOutOfRange { axis, value },
    cross_error: |row, col, value| CalibrationError::GyroCrossAxisOutOfRange { row, col, value },
};

impl Calibration {
    /// Checks that every value is finite and plausible for an MPU-6050; the reason when not.
    pub fn validate(&self) -> Result<(), CalibrationError> {
        self.check_finite()?;
        check_matrix(&self.matrix, &ACCEL_MATRIX)?;
        check_matrix(&self.gyro.matrix, &GYRO_MATRIX)?;
        check_bound(self.offset_g, limits::OFFSET_G)
            .map_err(|(axis, value_g)| CalibrationError::OffsetOutOfRange { axis, value_g })?;
        check_bound(self.gyro.bias_dps, limits::GYRO_BIAS_DPS)
            .map_err(|(axis, value_dps)| CalibrationError::GyroBiasOutOfRange { axis, value_dps })?;
        match &self.temperature {
            Some(model) => check_temperature(model),
            None => Ok(()),
        }
    }

    fn check_finite(&self) -> Result<(), CalibrationError> {
        let scalars = [self.mean_temp_c, self.residual_mg];
        let parts: [&[f32]; 5] = [
            self.matrix.as_flattened(),
            self.gyro.matrix.as_flattened(),
            &self.offset_g,
            &self.gyro.bias_dps,
            &scalars,
        ];
        let model_finite = self.temperature.as_ref().is_none_or(|model| model.values().all(|v| v.is_finite()));
        if model_finite && parts.iter().all(|part| part.iter().all(|v| v.is_finite())) {
            Ok(())
        } else {
            Err(CalibrationError::NonFinite)
        }
    }
}

fn check_matrix(matrix: &Mat3<f32>, bounds: &MatrixLimits) -> Result<(), CalibrationError> {
    let determinant = linalg::determinant(matrix);
    if determinant.abs() < limits::MIN_DETERMINANT {
        return Err((bounds.singular)(determinant));
    }
    for (row, cells) in matrix.iter().enumerate() {
        for (col, &value) in cells.iter().enumerate() {
            let (row, col) = (row as u8, col as u8);
            if row == col && !(bounds.scale.0..=bounds.scale.1).contains(&value) {
                return Err((bounds.scale_error)(row, value));
            }
            if row != col && value.abs() > bounds.cross_axis {
                return Err((bounds.cross_error)(row, col, value));
            }
        }
    }
    Ok(())
}

fn check_temperature(model: &TemperatureModel) -> Result<(), CalibrationError> {
    let (low, high) = limits::OPERATING_TEMP_C;
    if !(low..=high).contains(&model.ref_temp_c) {
        return Err(CalibrationError::ReferenceTemperatureOutOfRange { value_c: model.ref_temp_c });
    }
    check_drift(model, &model.offset_g, limits::OFFSET_DRIFT_G)
        .map_err(|(axis, value_g)| CalibrationError::OffsetDriftOutOfRange { axis, value_g })?;
    check_drift(model, &model.scale, limits::SCALE_DRIFT)
        .map_err(|(axis, value)| CalibrationError::ScaleDriftOutOfRange { axis, value })?;
    check_drift(model, &model.gyro_bias_dps, limits::GYRO_BIAS_DRIFT_DPS)
        .map_err(|(axis, value_dps)| CalibrationError::GyroBiasDriftOutOfRange { axis, value_dps })
}

/// The first drift beyond `limit` at evenly spaced temperatures across the operating range.
fn check_drift(model: &TemperatureModel, coefficients: &TempCoefficients, limit: f32) -> Result<(), (u8, f32)> {
    let (low, high) = limits::OPERATING_TEMP_C;
    for step in 0..=DRIFT_CHECK_STEPS {
        let temp_c = low + (high - low) * f32::from(step) / f32::from(DRIFT_CHECK_STEPS);
        check_bound(drift(coefficients, temp_c - model.ref_temp_c), limit)?;
    }
    Ok(())
}

/// The first component (axis, value) whose magnitude exceeds `limit`.
fn check_bound(values: Vec3<f32>, limit: f32) -> Result<(), (u8, f32)> {
    match values.iter().position(|v| v.abs() > limit) {
        Some(axis) => Err((axis as u8, values[axis])),
        None => Ok(()),
    }
}
