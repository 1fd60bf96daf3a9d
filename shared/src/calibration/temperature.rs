//! The temperature model of a calibration (DESIGN.md, "Conventions for the next capabilities"): the
//! accelerometer offset and scale and the gyro bias as polynomials in (T - T_ref), evaluated in f32.

use serde::{Deserialize, Serialize};

use crate::linalg::Vec3;

/// Highest power of (T - T_ref) a temperature model carries.
pub const MAX_TEMP_ORDER: usize = 3;

/// Coefficients of powers 1..=[`MAX_TEMP_ORDER`] of (T - T_ref), per axis: `[k - 1][axis]`.
pub type TempCoefficients = [Vec3<f32>; MAX_TEMP_ORDER];

/// How a calibration changes with the die temperature, around a reference temperature.
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq)]
pub struct TemperatureModel {
    /// T_ref in degC: the temperature at which the calibration's own M, o, G and b hold exactly.
    pub ref_temp_c: f32,
    /// c_k in g/degC^k: o(T) = o + sum_k c_k (T - T_ref)^k.
    pub offset_g: TempCoefficients,
    /// d_k in 1/degC^k: M(T) = M diag(1 + sum_k d_k (T - T_ref)^k)^-1 (zero where unobserved).
    pub scale: TempCoefficients,
    /// e_k in deg/s/degC^k: b(T) = b + sum_k e_k (T - T_ref)^k.
    pub gyro_bias_dps: TempCoefficients,
}

impl TemperatureModel {
    /// A model that changes nothing, around `ref_temp_c`.
    pub const fn flat(ref_temp_c: f32) -> Self {
        TemperatureModel {
            ref_temp_c,
            offset_g: [[0.0; 3]; MAX_TEMP_ORDER],
            scale: [[0.0; 3]; MAX_TEMP_ORDER],
            gyro_bias_dps: [[0.0; 3]; MAX_TEMP_ORDER],
        }
    }

    /// T - T_ref for a die temperature in degC, with T held to the operating range: the model is
    /// validated over that range only, so a wild temperature reading cannot make it blow up.
    pub fn delta_c(&self, temp_c: f32) -> f32 {
        let (low, high) = super::limits::OPERATING_TEMP_C;
        temp_c.clamp(low, high) - self.ref_temp_c
    }

    /// Every coefficient, T_ref first (for the finiteness check).
    pub fn values(&self) -> impl Iterator<Item = &f32> {
        let coefficients = self.offset_g.iter().chain(&self.scale).chain(&self.gyro_bias_dps).flatten();
        core::iter::once(&self.ref_temp_c).chain(coefficients)
    }
}

/// sum_k coefficients[k - 1] (T - T_ref)^k per axis, by Horner's rule.
pub fn drift(coefficients: &TempCoefficients, delta_c: f32) -> Vec3<f32> {
    let mut sum = [0.0f32; 3];
    for order in coefficients.iter().rev() {
        for axis in 0..3 {
            sum[axis] = (sum[axis] + order[axis]) * delta_c;
        }
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn drift_sums_each_power_of_the_temperature_difference() {
        let coefficients = [[1.0, 0.0, -2.0], [0.5, 0.0, 0.0], [0.25, 1.0, 0.0]];
        // dt = 2: x = 1*2 + 0.5*4 + 0.25*8 = 6; y = 8; z = -4.
        assert_eq!(drift(&coefficients, 2.0), [6.0, 8.0, -4.0]);
        assert_eq!(drift(&coefficients, 0.0), [0.0; 3]);
    }
}
