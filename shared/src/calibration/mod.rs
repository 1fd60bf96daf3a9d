//! The calibration model `a = M (m - o)`, its temperature model and the gyro correction
//! `w = G (w_raw - b)`, with the checks that keep absurd calibrations off the chip.

mod origin;
mod temperature;
mod validate;

use serde::{Deserialize, Serialize};

use crate::linalg::{self, Mat3, Vec3};
use crate::protocol::LowPassFilter;

pub use origin::{ModelTag, Origin, Procedure, MODEL_TAG_LEN};
pub use temperature::{drift, TempCoefficients, TemperatureModel, MAX_TEMP_ORDER};
pub use validate::{limits, CalibrationError};

/// Full-scale range of the MPU-6050 accelerometer (register ACCEL_CONFIG, AFS_SEL).
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq, Eq, Default)]
// NOTE: a JSON file spells each variant as a person reads it (issue 40: sessions said "G2", "Hz44",
// "HostFit"); the old spellings are still read. postcard (the wire and the flash) keeps the variant's
// index, so the renames change no byte there.
pub enum AccelRange {
    /// +-2 g, 16384 LSB/g (the default).
    #[default]
    #[serde(rename = "2g", alias = "G2")]
    G2,
    /// +-4 g, 8192 LSB/g.
    #[serde(rename = "4g", alias = "G4")]
    G4,
    /// +-8 g, 4096 LSB/g.
    #[serde(rename = "8g", alias = "G8")]
    G8,
    /// +-16 g, 2048 LSB/g.
    #[serde(rename = "16g", alias = "G16")]
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

/// Standard gravity, m/s^2 per g: the g every value in m/s^2 is converted with (CGPM 1901, 3rd
/// meeting; ISO 80000-3; the value ArduPilot's GRAVITY_MSS, PX4's CONSTANTS_ONE_G and Adafruit's
/// SENSORS_GRAVITY_STANDARD use).
pub const STANDARD_GRAVITY: f64 = 9.80665;

/// Full-scale range of the MPU-6050 gyro (register GYRO_CONFIG, FS_SEL 0-3).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GyroRange {
    /// +-250 deg/s, 131 LSB per deg/s (FS_SEL 0; the range every family's self-test trim assumes).
    Dps250 = 0,
    /// +-500 deg/s, 65.5 LSB per deg/s.
    Dps500 = 1,
    /// +-1000 deg/s, 32.8 LSB per deg/s.
    Dps1000 = 2,
    /// +-2000 deg/s, 16.4 LSB per deg/s.
    Dps2000 = 3,
}

impl GyroRange {
    /// Sensitivity in LSB per deg/s (MPU-6000/6050 Product Specification rev 3.4, section 6.1; the
    /// table's own rounded figures, not 131 halved).
    ///
    /// NOTE: f64, unlike [`AccelRange::lsb_per_g`]'s powers of two: 32.8 and 16.4 have no exact
    /// binary form, and the host prints them (exports); the chip takes `as f32` in a `const`, which
    /// is the nearest f32 to the printed figure.
    pub const fn lsb_per_dps(self) -> f64 {
        match self {
            GyroRange::Dps250 => 131.0,
            GyroRange::Dps500 => 65.5,
            GyroRange::Dps1000 => 32.8,
            GyroRange::Dps2000 => 16.4,
        }
    }

    /// Full scale in deg/s.
    pub const fn full_scale_dps(self) -> u16 {
        match self {
            GyroRange::Dps250 => 250,
            GyroRange::Dps500 => 500,
            GyroRange::Dps1000 => 1000,
            GyroRange::Dps2000 => 2000,
        }
    }

    /// The range GYRO_CONFIG's FS_SEL field (0-3, register map section 4.4) selects; its two low
    /// bits only.
    pub const fn from_fs_sel(fs_sel: u8) -> Self {
        match fs_sel & 0x03 {
            0 => GyroRange::Dps250,
            1 => GyroRange::Dps500,
            2 => GyroRange::Dps1000,
            _ => GyroRange::Dps2000,
        }
    }

    /// GYRO_CONFIG's FS_SEL field for this range (register map section 4.4).
    pub const fn fs_sel(self) -> u8 {
        self as u8
    }
}

/// The gyro correction `w = G (w_raw - b)`, in deg/s.
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq)]
pub struct GyroCalibration {
    /// Scale and misalignment matrix G (row-major, dimensionless; identity when not fitted).
    pub matrix: Mat3<f32>,
    /// Bias b in deg/s at the reference temperature, subtracted before G is applied.
    pub bias_dps: Vec3<f32>,
}

impl Default for GyroCalibration {
    fn default() -> Self {
        GyroCalibration { matrix: linalg::identity(), bias_dps: [0.0; 3] }
    }
}

/// A complete calibration for one sensor at one range: `a = M (m - o)` in g, `w = G (w_raw - b)` in
/// deg/s, both optionally varying with temperature.
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq)]
pub struct Calibration {
    /// Which procedure and model made it.
    pub origin: Origin,
    /// The accelerometer range the calibration belongs to.
    pub range: AccelRange,
    /// The low-pass filter the captures were taken through (it shapes the noise the residual and
    /// the still checks saw, and the group delay of corrected samples).
    pub filter: LowPassFilter,
    /// Correction matrix M (row-major, dimensionless).
    pub matrix: Mat3<f32>,
    /// Offset o in g, subtracted before M is applied.
    pub offset_g: Vec3<f32>,
    /// The gyro correction.
    pub gyro: GyroCalibration,
    /// Mean die temperature of the captures the calibration was fitted from, in degC.
    pub mean_temp_c: f32,
    /// How offset, scale and gyro bias change with temperature; `None`: they do not.
    pub temperature: Option<TemperatureModel>,
    /// RMS fit residual in mg (0 for an exactly determined fit).
    pub residual_mg: f32,
}

impl Calibration {
    /// The identity calibration: samples pass through unchanged.
    pub fn identity(range: AccelRange) -> Self {
        Calibration {
            origin: Origin::IDENTITY,
            range,
            filter: LowPassFilter::default(),
            matrix: linalg::identity(),
            offset_g: [0.0; 3],
            gyro: GyroCalibration::default(),
            mean_temp_c: 0.0,
            temperature: None,
            residual_mg: 0.0,
        }
    }

    /// Corrects one accelerometer reading in g without a temperature: `a = M (m - o)`.
    pub fn apply(&self, reading_g: Vec3<f32>) -> Vec3<f32> {
        linalg::mul_vec(&self.matrix, linalg::sub(reading_g, self.offset_g))
    }

    /// Corrects one accelerometer reading in g taken at `temp_c` degC: `a = M(T) (m - o(T))`, with
    /// o(T) = o + sum c_k dT^k and M(T) = M diag(1 + sum d_k dT^k)^-1; [`Self::apply`] without a model.
    pub fn apply_at(&self, reading_g: Vec3<f32>, temp_c: f32) -> Vec3<f32> {
        let Some((offset, scale)) = self.accel_terms_at(temp_c) else {
            return self.apply(reading_g);
        };
        let centred = linalg::sub(reading_g, offset);
        // NOTE: validation keeps |scale drift| well below 1 over the operating range, so 1 + drift > 0.
        let unscaled = [0, 1, 2].map(|axis| centred[axis] / (1.0 + scale[axis]));
        linalg::mul_vec(&self.matrix, unscaled)
    }

    /// The temperature model's accelerometer terms at `temp_c` degC: the offset o(T) = o + sum c_k dT^k
    /// in g and each axis' scale drift sum d_k dT^k (M(T) = M diag(1 + drift)^-1); `None` without a
    /// model. The one evaluation of the model: [`Self::apply_at`] on the chip, M(T) and o(T) on the host.
    // NOTE: inlined into the chip's apply_at / apply_gyro: measured on the Black Pill F411, text 64 448 B
    // with it, 64 484 B as a call, 64 456 B before these terms had their own function.
    #[inline(always)]
    pub fn accel_terms_at(&self, temp_c: f32) -> Option<(Vec3<f32>, Vec3<f32>)> {
        let model = self.temperature.as_ref()?;
        let delta_c = model.delta_c(temp_c);
        Some((linalg::add(self.offset_g, drift(&model.offset_g, delta_c)), drift(&model.scale, delta_c)))
    }

    /// The gyro bias b(T) = b + sum e_k dT^k at `temp_c` degC, in deg/s (b without a model).
    // NOTE: inlined into the chip's apply_at / apply_gyro: measured on the Black Pill F411, text 64 448 B
    // with it, 64 484 B as a call, 64 456 B before these terms had their own function.
    #[inline(always)]
    pub fn gyro_bias_at(&self, temp_c: f32) -> Vec3<f32> {
        match &self.temperature {
            Some(model) => linalg::add(self.gyro.bias_dps, drift(&model.gyro_bias_dps, model.delta_c(temp_c))),
            None => self.gyro.bias_dps,
        }
    }

    /// Corrects one gyro reading in deg/s taken at `temp_c` degC: `w = G (w_raw - b(T))`, with
    /// b(T) = b + sum e_k dT^k (b alone without a temperature model).
    pub fn apply_gyro(&self, reading_dps: Vec3<f32>, temp_c: f32) -> Vec3<f32> {
        linalg::mul_vec(&self.gyro.matrix, linalg::sub(reading_dps, self.gyro_bias_at(temp_c)))
    }
}

#[cfg(test)]
mod tests;
