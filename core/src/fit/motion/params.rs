//! The joint fit's unknowns as one vector: the sensor model's 31 numbers, then each rest's
//! orientation as a small world-frame rotation about its current estimate (two for the first rest:
//! the world's heading is arbitrary, so the first rest's turn about the vertical is held).

use nalgebra::{Matrix3, Vector3};

use super::JointModel;

/// The upper-triangular entries of M, in the order the vector holds them.
pub(super) const ACCEL_ENTRIES: [(usize, usize); 6] = [(0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2)];
/// Where each part of the model sits in the vector.
pub(super) const OFFSET: usize = 6;
pub(super) const GYRO_MATRIX: usize = 9;
pub(super) const GYRO_BIAS: usize = 18;
pub(super) const G_SENSITIVITY: usize = 21;
pub(super) const SKEW: usize = 30;
/// The model's numbers; the orientations follow.
pub(super) const MODEL: usize = 31;
/// The accelerometer's numbers (M's six, o's three): what a prediction at a fresh orientation needs.
pub(super) const ACCEL: usize = 9;

/// The model as its 31 numbers.
pub(super) fn vector_of(model: &JointModel) -> Vec<f64> {
    let mut v = vec![0.0; MODEL];
    ACCEL_ENTRIES.iter().enumerate().for_each(|(k, &(i, j))| v[k] = model.accel_matrix[(i, j)]);
    v[OFFSET..OFFSET + 3].copy_from_slice(model.accel_offset_g.as_slice());
    v[GYRO_MATRIX..GYRO_MATRIX + 9].copy_from_slice(model.gyro_matrix.transpose().as_slice());
    v[GYRO_BIAS..GYRO_BIAS + 3].copy_from_slice(model.gyro_bias_dps.as_slice());
    v[G_SENSITIVITY..G_SENSITIVITY + 9].copy_from_slice(model.g_sensitivity_dps_per_g.transpose().as_slice());
    v[SKEW] = model.skew_s;
    v
}

/// The model from its 31 numbers (matrices row by row).
pub(super) fn model_of(v: &[f64]) -> JointModel {
    let mut accel_matrix = Matrix3::zeros();
    ACCEL_ENTRIES.iter().enumerate().for_each(|(k, &(i, j))| accel_matrix[(i, j)] = v[k]);
    JointModel {
        accel_matrix,
        accel_offset_g: Vector3::from_column_slice(&v[OFFSET..OFFSET + 3]),
        gyro_matrix: Matrix3::from_row_slice(&v[GYRO_MATRIX..GYRO_MATRIX + 9]),
        gyro_bias_dps: Vector3::from_column_slice(&v[GYRO_BIAS..GYRO_BIAS + 3]),
        g_sensitivity_dps_per_g: Matrix3::from_row_slice(&v[G_SENSITIVITY..G_SENSITIVITY + 9]),
        skew_s: v[SKEW],
    }
}

/// The step of the forward differences on each model number: about sqrt(eps) of its size (the
/// skew is a few milliseconds, S a tenth of a deg/s per g, b a degree per second).
pub(super) fn difference_step(index: usize) -> f64 {
    match index {
        SKEW => 1e-7,
        GYRO_BIAS..SKEW => 1e-6,
        _ => 1e-7,
    }
}

/// The column of rest `k`'s orientation axis `axis` (world x, y, z), or `None` for the first
/// rest's vertical; the first rest has two columns, every later one three.
pub(super) fn orientation_column(k: usize, axis: usize) -> Option<usize> {
    match k {
        0 => (axis < 2).then_some(MODEL + axis),
        _ => Some(MODEL + 2 + 3 * (k - 1) + axis),
    }
}

/// Columns in all for `rests` rests.
pub(super) fn columns(rests: usize) -> usize {
    MODEL + 3 * rests - 1
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_model_survives_its_vector() {
        let model = JointModel {
            accel_matrix: Matrix3::new(1.01, 0.002, -0.003, 0.0, 0.99, 0.004, 0.0, 0.0, 1.02),
            accel_offset_g: Vector3::new(0.03, -0.01, 0.05),
            gyro_matrix: Matrix3::new(1.0, 0.01, 0.02, 0.03, 0.98, 0.04, 0.05, 0.06, 1.03),
            gyro_bias_dps: Vector3::new(-1.2, 0.8, 0.35),
            g_sensitivity_dps_per_g: Matrix3::new(0.1, 0.01, 0.02, 0.03, 0.1, 0.04, 0.05, 0.06, 0.1),
            skew_s: -1e-4,
        };
        assert_eq!(model_of(&vector_of(&model)), model);
    }
}
