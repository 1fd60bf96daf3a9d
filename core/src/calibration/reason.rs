//! Why a calibration was refused (by the host's checks or the chip's), in words, with the limit it
//! broke.

use shared::calibration::limits;
use shared::CalibrationError;

/// Why a calibration was refused, in words, with the limit it broke (`shared::calibration::limits`).
pub fn calibration_reason(reason: &CalibrationError) -> String {
    match *reason {
        CalibrationError::NonFinite => "it holds a value that is not a number".into(),
        CalibrationError::Singular { determinant } => format!("its matrix is singular (determinant {determinant:.3})"),
        CalibrationError::ScaleOutOfRange { axis, value } => {
            let (low, high) = limits::SCALE;
            format!("the {} scale {value:.3} is outside {low}-{high}", axis_name(axis))
        }
        CalibrationError::CrossAxisOutOfRange { row, col, value } => {
            format!("cross-axis term M{}{} = {value:.3} is larger than {}", row + 1, col + 1, limits::CROSS_AXIS)
        }
        CalibrationError::OffsetOutOfRange { axis, value_g } => {
            format!("the {} offset {value_g:.3} g is larger than {} g", axis_name(axis), limits::OFFSET_G)
        }
        _ => gyro_or_drift_reason(reason),
    }
}

/// The refusals of the gyro correction and of the temperature model.
fn gyro_or_drift_reason(reason: &CalibrationError) -> String {
    let (low_c, high_c) = limits::OPERATING_TEMP_C;
    let over = format!("somewhere in {low_c}..{high_c} degC");
    match *reason {
        CalibrationError::GyroBiasOutOfRange { axis, value_dps } => {
            format!(
                "the {} gyro bias {value_dps:.1} deg/s is larger than {} deg/s",
                axis_name(axis),
                limits::GYRO_BIAS_DPS
            )
        }
        CalibrationError::GyroSingular { determinant } => {
            format!("its gyro matrix is singular (determinant {determinant:.3})")
        }
        CalibrationError::GyroScaleOutOfRange { axis, value } => {
            let (low, high) = limits::GYRO_SCALE;
            format!("the {} gyro scale {value:.3} is outside {low}-{high}", axis_name(axis))
        }
        CalibrationError::GyroCrossAxisOutOfRange { row, col, value } => {
            let limit = limits::GYRO_CROSS_AXIS;
            format!("gyro cross-axis term G{}{} = {value:.3} is larger than {limit}", row + 1, col + 1)
        }
        CalibrationError::ReferenceTemperatureOutOfRange { value_c } => {
            format!("its reference temperature {value_c:.1} degC is outside {low_c}..{high_c} degC")
        }
        _ => drift_reason(reason, &over),
    }
}

/// The refusals of a temperature model whose drift is implausible `over` the operating range.
fn drift_reason(reason: &CalibrationError, over: &str) -> String {
    match *reason {
        CalibrationError::OffsetDriftOutOfRange { axis, value_g } => {
            let limit = limits::OFFSET_DRIFT_G;
            format!("the {} offset drifts by {value_g:.3} g {over}, more than {limit} g", axis_name(axis))
        }
        CalibrationError::ScaleDriftOutOfRange { axis, value } => {
            let limit = limits::SCALE_DRIFT;
            format!("the {} scale drifts by {value:.3} {over}, more than {limit}", axis_name(axis))
        }
        CalibrationError::GyroBiasDriftOutOfRange { axis, value_dps } => {
            let limit = limits::GYRO_BIAS_DRIFT_DPS;
            format!("the {} gyro bias drifts by {value_dps:.1} deg/s {over}, more than {limit} deg/s", axis_name(axis))
        }
        _ => format!("{reason:?}"),
    }
}

fn axis_name(axis: u8) -> &'static str {
    ["x", "y", "z"].get(usize::from(axis)).copied().unwrap_or("?")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refusal_reasons_quote_the_limits_they_broke() {
        let offset = CalibrationError::OffsetOutOfRange { axis: 0, value_g: 3.0 };
        assert_eq!(calibration_reason(&offset), "the x offset 3.000 g is larger than 0.5 g");
        let scale = CalibrationError::ScaleOutOfRange { axis: 2, value: 3.0 };
        assert_eq!(calibration_reason(&scale), "the z scale 3.000 is outside 0.5-2");
    }
}
