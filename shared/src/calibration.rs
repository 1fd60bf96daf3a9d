//! The calibration model `a = M (m - o)` and the checks that keep absurd calibrations off the chip.

use serde::{Deserialize, Serialize};

use crate::linalg::{self, Mat3, Vec3};

/// The fitting model that produced a calibration (see DESIGN.md for the shape of M in each).
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq, Eq)]
pub enum Model {
    /// Closed form from the six axis-aligned positions, full M; the model fitted on the chip.
    SixPosition,
    /// Linear least squares over positions of known orientation, full M.
    Linear12,
    /// Known-orientation rows plus |a| = g rows (Ivanov et al.), full M.
    ReferenceNorm12,
    /// Upper-unit-triangular T times diagonal K, orientation-free.
    Ortho9,
    /// Diagonal M, orientation-free.
    Diag6,
}

impl Model {
    /// The model's name as used on the command line and in JSON.
    pub const fn name(self) -> &'static str {
        match self {
            Model::SixPosition => "six-position",
            Model::Linear12 => "linear12",
            Model::ReferenceNorm12 => "reference-norm12",
            Model::Ortho9 => "ortho9",
            Model::Diag6 => "diag6",
        }
    }
}

/// Full-scale range of the MPU-6050 accelerometer (register ACCEL_CONFIG, AFS_SEL).
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum AccelRange {
    /// +-2 g, 16384 LSB/g (the default).
    #[default]
    G2,
    /// +-4 g, 8192 LSB/g.
    G4,
    /// +-8 g, 4096 LSB/g.
    G8,
    /// +-16 g, 2048 LSB/g.
    G16,
}

impl AccelRange {
    /// Sensitivity in LSB per g (MPU-6000/6050 Product Specification rev 3.4, section 6.2).
    pub const fn lsb_per_g(self) -> f32 {
        match self {
            AccelRange::G2 => 16384.0,
            AccelRange::G4 => 8192.0,
            AccelRange::G8 => 4096.0,
            AccelRange::G16 => 2048.0,
        }
    }

    /// Full scale in g.
    pub const fn full_scale_g(self) -> u8 {
        match self {
            AccelRange::G2 => 2,
            AccelRange::G4 => 4,
            AccelRange::G8 => 8,
            AccelRange::G16 => 16,
        }
    }

    /// The range with the given full scale in g, if the sensor has one.
    pub const fn from_full_scale_g(full_scale_g: u8) -> Option<Self> {
        match full_scale_g {
            2 => Some(AccelRange::G2),
            4 => Some(AccelRange::G4),
            8 => Some(AccelRange::G8),
            16 => Some(AccelRange::G16),
            _ => None,
        }
    }
}

/// Limits outside which a calibration is refused as absurd for an MPU-6050.
///
/// NOTE: the datasheet allows +-3 % sensitivity tolerance and +-2 % cross-axis sensitivity
/// (MPU-6050 Product Specification section 6.2); the limits leave a wide margin for misalignment of
/// the sensor on its board while still rejecting a fit that went wrong.
pub mod limits {
    /// Each diagonal element of M must lie in this range.
    pub const SCALE: (f32, f32) = (0.5, 2.0);
    /// Largest magnitude allowed for an off-diagonal element of M.
    pub const CROSS_AXIS: f32 = 0.25;
    /// Smallest |det M|; below this M is treated as singular.
    pub const MIN_DETERMINANT: f32 = 0.1;
    /// Largest magnitude of an offset component, in g (zero-g offset spec is +-80 mg x/y, +-150 mg z).
    pub const OFFSET_G: f32 = 0.5;
    /// Largest magnitude of a gyro bias component, in deg/s (spec: +-20 deg/s).
    pub const GYRO_BIAS_DPS: f32 = 50.0;
}

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
}

/// A complete calibration for one sensor at one range: `a = M (m - o)`, all in g.
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq)]
pub struct Calibration {
    /// Correction matrix M (row-major, dimensionless).
    pub matrix: Mat3<f32>,
    /// Offset o in g, subtracted before M is applied.
    pub offset_g: Vec3<f32>,
    /// Gyro bias in deg/s, subtracted from every gyro sample.
    pub gyro_bias_dps: Vec3<f32>,
    /// The model that produced the calibration.
    pub model: Model,
    /// The accelerometer range the calibration belongs to.
    pub range: AccelRange,
    /// Mean sensor temperature during the captures, in degC.
    pub temp_c: f32,
    /// RMS fit residual in mg (0 for an exactly determined fit).
    pub residual_mg: f32,
}

impl Calibration {
    /// The identity calibration: samples pass through unchanged.
    pub fn identity(range: AccelRange) -> Self {
        Calibration {
            matrix: linalg::identity(),
            offset_g: [0.0; 3],
            gyro_bias_dps: [0.0; 3],
            model: Model::SixPosition,
            range,
            temp_c: 0.0,
            residual_mg: 0.0,
        }
    }

    /// Corrects one accelerometer reading in g: `a = M (m - o)`.
    pub fn apply(&self, reading_g: Vec3<f32>) -> Vec3<f32> {
        linalg::mul_vec(&self.matrix, linalg::sub(reading_g, self.offset_g))
    }

    /// Removes the gyro bias from one gyro reading in deg/s.
    pub fn apply_gyro(&self, reading_dps: Vec3<f32>) -> Vec3<f32> {
        linalg::sub(reading_dps, self.gyro_bias_dps)
    }

    /// Checks that every value is finite and plausible for an MPU-6050; the reason when not.
    pub fn validate(&self) -> Result<(), CalibrationError> {
        self.check_finite()?;
        self.check_matrix()?;
        check_bound(self.offset_g, limits::OFFSET_G)
            .map_err(|(axis, value_g)| CalibrationError::OffsetOutOfRange { axis, value_g })?;
        check_bound(self.gyro_bias_dps, limits::GYRO_BIAS_DPS)
            .map_err(|(axis, value_dps)| CalibrationError::GyroBiasOutOfRange { axis, value_dps })
    }

    fn check_finite(&self) -> Result<(), CalibrationError> {
        let scalars = [self.temp_c, self.residual_mg];
        let all = self.matrix.iter().flatten().chain(&self.offset_g).chain(&self.gyro_bias_dps);
        if all.chain(&scalars).all(|v| v.is_finite()) {
            Ok(())
        } else {
            Err(CalibrationError::NonFinite)
        }
    }

    fn check_matrix(&self) -> Result<(), CalibrationError> {
        let determinant = linalg::determinant(&self.matrix);
        if determinant.abs() < limits::MIN_DETERMINANT {
            return Err(CalibrationError::Singular { determinant });
        }
        for (row, cells) in self.matrix.iter().enumerate() {
            for (col, &value) in cells.iter().enumerate() {
                let (row, col) = (row as u8, col as u8);
                if row == col && !(limits::SCALE.0..=limits::SCALE.1).contains(&value) {
                    return Err(CalibrationError::ScaleOutOfRange { axis: row, value });
                }
                if row != col && value.abs() > limits::CROSS_AXIS {
                    return Err(CalibrationError::CrossAxisOutOfRange { row, col, value });
                }
            }
        }
        Ok(())
    }
}

/// The first component (axis, value) whose magnitude exceeds `limit`.
fn check_bound(values: Vec3<f32>, limit: f32) -> Result<(), (u8, f32)> {
    match values.iter().position(|v| v.abs() > limit) {
        Some(axis) => Err((axis as u8, values[axis])),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plausible() -> Calibration {
        Calibration {
            matrix: [[1.01, 0.002, -0.007], [0.0, 0.997, 0.0005], [0.0, 0.0, 1.017]],
            offset_g: [0.0276, -0.0057, -0.0783],
            gyro_bias_dps: [-1.5, 0.8, 0.2],
            ..Calibration::identity(AccelRange::G2)
        }
    }

    #[test]
    fn apply_subtracts_offset_then_multiplies() {
        let cal = Calibration {
            matrix: [[2.0, 0.0, 0.0], [0.0, 1.0, 0.5], [0.0, 0.0, 1.0]],
            offset_g: [0.5, 0.0, 1.0],
            ..Calibration::identity(AccelRange::G2)
        };
        // m - o = (0.5, 1, 1); M (m - o) = (1.0, 1.5, 1.0)
        assert_eq!(cal.apply([1.0, 1.0, 2.0]), [1.0, 1.5, 1.0]);
    }

    #[test]
    fn plausible_calibration_is_accepted() {
        assert_eq!(plausible().validate(), Ok(()));
    }

    #[test]
    fn non_finite_values_are_refused() {
        let mut cal = plausible();
        cal.offset_g[1] = f32::NAN;
        assert_eq!(cal.validate(), Err(CalibrationError::NonFinite));
        let mut cal = plausible();
        cal.matrix[2][0] = f32::INFINITY;
        assert_eq!(cal.validate(), Err(CalibrationError::NonFinite));
    }

    #[test]
    fn singular_matrix_is_refused() {
        let mut cal = plausible();
        cal.matrix = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 0.0]];
        assert!(matches!(cal.validate(), Err(CalibrationError::Singular { .. })));
    }

    #[test]
    fn absurd_scale_cross_axis_and_offset_are_refused_with_the_axis() {
        let mut cal = plausible();
        cal.matrix[1][1] = 3.0;
        assert_eq!(cal.validate(), Err(CalibrationError::ScaleOutOfRange { axis: 1, value: 3.0 }));
        let mut cal = plausible();
        cal.matrix[0][2] = 0.4;
        assert_eq!(cal.validate(), Err(CalibrationError::CrossAxisOutOfRange { row: 0, col: 2, value: 0.4 }));
        let mut cal = plausible();
        cal.offset_g[2] = -0.9;
        assert_eq!(cal.validate(), Err(CalibrationError::OffsetOutOfRange { axis: 2, value_g: -0.9 }));
    }

    #[test]
    fn range_sensitivities_follow_the_datasheet() {
        for (range, lsb) in [(AccelRange::G2, 16384.0), (AccelRange::G16, 2048.0)] {
            assert_eq!(range.lsb_per_g(), lsb);
            assert_eq!(AccelRange::from_full_scale_g(range.full_scale_g()), Some(range));
        }
        assert_eq!(AccelRange::from_full_scale_g(3), None);
    }
}
