//! The map from a data file's units to the solver's: an axis-aligned ellipsoid fitted to the
//! readings gives a centre c and radii r, and the solver sees m' = (m - c) / r, where the answer is
//! near M' = I, o' = 0 whatever the file's unit.

use nalgebra::{Vector3, Vector6};

use super::linearised::Gram;

/// The centre and per-axis radius of the readings: the map to the solver's units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Normalization {
    pub center: [f64; 3],
    pub radii: [f64; 3],
}

impl Normalization {
    /// From an axis-aligned ellipsoid fit (x^2, y^2, z^2, x, y, z) = 1 by least squares; from the mean
    /// and spread when the readings do not determine an ellipsoid.
    pub(super) fn from_readings(readings: &[[f64; 3]]) -> Self {
        Self::ellipsoid(readings).unwrap_or_else(|| Self::spread(readings))
    }

    /// From the readings of every row of a data set.
    pub(super) fn of_dataset(dataset: &crate::data::Dataset) -> Self {
        let readings: Vec<[f64; 3]> = dataset.rows.iter().map(|r| r.reading).collect();
        Self::from_readings(&readings)
    }

    fn ellipsoid(readings: &[[f64; 3]]) -> Option<Self> {
        if readings.len() < 6 {
            return None;
        }
        // NOTE: scale first, so that raw counts of 1e6 do not make x^2 terms of 1e12.
        let Normalization { center, radii } = Self::spread(readings);
        let scaled: Vec<Vector3<f64>> =
            readings.iter().map(|m| Vector3::from_fn(|k, _| (m[k] - center[k]) / radii[k])).collect();
        let beta = quadric_coefficients(&scaled)?;
        let (quadratic, linear) = (beta.fixed_rows::<3>(0), beta.fixed_rows::<3>(3));
        if quadratic.iter().any(|&a| a <= 0.0 || !a.is_finite()) {
            return None;
        }
        let shift = Vector3::from_fn(|k, _| -linear[k] / (2.0 * quadratic[k]));
        let level = 1.0 + (0..3).map(|k| quadratic[k] * shift[k] * shift[k]).sum::<f64>();
        if level <= 0.0 {
            return None;
        }
        let new_radii = [0, 1, 2].map(|k| (level / quadratic[k]).sqrt() * radii[k]);
        let new_center = [0, 1, 2].map(|k| center[k] + shift[k] * radii[k]);
        new_radii
            .iter()
            .chain(&new_center)
            .all(|v| v.is_finite())
            .then_some(Normalization { center: new_center, radii: new_radii })
    }

    fn spread(readings: &[[f64; 3]]) -> Self {
        let n = readings.len().max(1) as f64;
        let center = [0, 1, 2].map(|k| readings.iter().map(|m| m[k]).sum::<f64>() / n);
        let rms =
            (readings.iter().map(|m| (0..3).map(|k| (m[k] - center[k]).powi(2)).sum::<f64>()).sum::<f64>() / n).sqrt();
        let radius = if rms > 0.0 && rms.is_finite() { rms } else { 1.0 };
        Normalization { center, radii: [radius; 3] }
    }

    /// m' = (m - c) / r.
    pub(super) fn apply(&self, reading: [f64; 3]) -> Vector3<f64> {
        Vector3::from_fn(|k, _| (reading[k] - self.center[k]) / self.radii[k])
    }
}

/// The coefficients (a, b) of sum_k a_k x_k^2 + b_k x_k = 1 fitted to readings scaled to order one.
fn quadric_coefficients(scaled: &[Vector3<f64>]) -> Option<Vector6<f64>> {
    // Normal equations: with the readings scaled to order one, the 6 x 6 system is well conditioned
    // whenever the readings determine an ellipsoid at all, and Cholesky says when they do not.
    let (mut normal, mut right) = (Gram::<6>::new(), Vector6::zeros());
    for v in scaled {
        let row = Vector6::new(v[0] * v[0], v[1] * v[1], v[2] * v[2], v[0], v[1], v[2]);
        normal.add(&row, &row);
        right += row;
    }
    Some(normal.matrix().cholesky()?.solve(&right))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ellipsoid_start_finds_centre_and_radii_of_raw_counts() {
        // Twelve directions on a sensor of 1e6 counts per g with offsets of tens of thousands.
        let center = [-43681.0, -29517.0, 20533.0];
        let radii = [0.99e6, 1.006e6, 0.9996e6];
        let directions = [
            [1.0, 0.0, 0.0],
            [-1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, -1.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.0, 0.0, -1.0],
            [0.6, 0.8, 0.0],
            [0.0, -0.6, 0.8],
            [-0.8, 0.0, -0.6],
            [0.48, 0.6, 0.64],
            [-0.6, -0.48, 0.64],
            [0.6, -0.64, -0.48],
        ];
        let readings: Vec<[f64; 3]> =
            directions.iter().map(|d: &[f64; 3]| [0, 1, 2].map(|k| center[k] + radii[k] * d[k])).collect();
        let found = Normalization::from_readings(&readings);
        for k in 0..3 {
            assert!((found.center[k] - center[k]).abs() < 1e-3, "centre {k}: {}", found.center[k]);
            assert!((found.radii[k] / radii[k] - 1.0).abs() < 1e-9, "radius {k}: {}", found.radii[k]);
        }
    }
}
