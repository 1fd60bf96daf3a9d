//! What a target loses: the one computation of the error left when a target applies only part of the
//! calibration, over the sphere of orientations, for this unit.
//!
//! The full calibration is taken as the truth: at a true specific force u (|u| = 1 g) the sensor reads
//! m = M^-1 u + o; the target applies its own M', o' and gives M' (m - o'). The loss is |M' (m - o') - u|
//! over [`SPHERE_POINTS`] orientations spread evenly over the sphere. The gyro's loss is the same with
//! G, b and a unit rate, as a fraction of the rate.

use shared::linalg::{self, Mat3, Vec3};

/// Orientations the loss is taken over (a Fibonacci lattice: evenly spread, the same every run).
pub const SPHERE_POINTS: usize = 10_000;

/// What a target carries of the calibration, in accelcal's convention a = M (m - o), w = G (w_raw - b).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Carried {
    /// The matrix the target applies (diagonal for a scale-only target, the identity for offsets only).
    pub matrix: Mat3<f64>,
    /// The offset the target subtracts, in g, as written (after the target's own rounding).
    pub offset_g: Vec3<f64>,
    /// The gyro matrix the target applies (the identity where it has none).
    pub gyro_matrix: Mat3<f64>,
    /// The gyro bias the target subtracts, in deg/s; `None` where it keeps none.
    pub gyro_bias_dps: Option<Vec3<f64>>,
}

/// The error a target leaves, for this unit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Loss {
    /// RMS over the sphere of |a_target - a|, in mg.
    pub rms_mg: f64,
    /// Largest over the sphere of |a_target - a|, in mg.
    pub worst_mg: f64,
    /// RMS over rate directions of |w_target - w| / |w|, in % (the gyro bias aside).
    pub gyro_rms_pct: f64,
    /// Largest over rate directions of |w_target - w| / |w|, in %.
    pub gyro_worst_pct: f64,
}

/// A point `i` of `n` on the unit sphere (Fibonacci lattice).
pub fn sphere_point(i: usize, n: usize) -> Vec3<f64> {
    let golden_angle = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    let z = 1.0 - (2.0 * i as f64 + 1.0) / n as f64;
    let r = (1.0 - z * z).sqrt();
    let phi = golden_angle * i as f64;
    [r * phi.cos(), r * phi.sin(), z]
}

/// The loss of `carried` against the full calibration (M, o) and (G, b).
pub fn loss(full: &Carried, carried: &Carried) -> Loss {
    let accel = spread(&full.matrix, &full.offset_g, &carried.matrix, &carried.offset_g);
    let gyro = spread(&full.gyro_matrix, &[0.0; 3], &carried.gyro_matrix, &[0.0; 3]);
    Loss { rms_mg: accel.0 * 1e3, worst_mg: accel.1 * 1e3, gyro_rms_pct: gyro.0 * 1e2, gyro_worst_pct: gyro.1 * 1e2 }
}

/// RMS and largest |M' (m - o') - u| over the sphere, where m = M^-1 u + o.
pub fn spread(matrix: &Mat3<f64>, offset: &Vec3<f64>, target: &Mat3<f64>, target_offset: &Vec3<f64>) -> (f64, f64) {
    let Some(inverse) = linalg::inverse(matrix) else {
        return (f64::NAN, f64::NAN);
    };
    let (mut sum, mut worst) = (0.0, 0.0f64);
    for i in 0..SPHERE_POINTS {
        let u = sphere_point(i, SPHERE_POINTS);
        let reading = linalg::add(linalg::mul_vec(&inverse, u), *offset);
        let error = linalg::norm(linalg::sub(linalg::mul_vec(target, linalg::sub(reading, *target_offset)), u));
        sum += error * error;
        worst = worst.max(error);
    }
    (mutant!("export-loss-rms-unmeaned", (sum / SPHERE_POINTS as f64).sqrt(), sum.sqrt()), worst)
}

/// The diagonal scale that leaves the least error over the sphere when only a scale per axis is kept:
/// s_i = (M^-1)_ii / |row i of M^-1|^2, the least-squares solution of s_i (M^-1 u)_i = u_i over
/// uniformly spread u (whose second moment is I/3).
pub fn best_diagonal(matrix: &Mat3<f64>) -> Vec3<f64> {
    let Some(inverse) = linalg::inverse(matrix) else {
        return [matrix[0][0], matrix[1][1], matrix[2][2]];
    };
    [0, 1, 2].map(|i| inverse[i][i] / linalg::dot(inverse[i], inverse[i]))
}

/// A diagonal matrix.
pub fn diagonal(scale: Vec3<f64>) -> Mat3<f64> {
    [[scale[0], 0.0, 0.0], [0.0, scale[1], 0.0], [0.0, 0.0, scale[2]]]
}

#[cfg(test)]
mod tests {
    use super::*;

    const M: Mat3<f64> = [[1.002, 0.004, -0.007], [0.0, 0.997, 0.003], [0.0, 0.0, 1.011]];
    const O: Vec3<f64> = [0.02, -0.01, 0.05];

    #[test]
    fn offsets_only_leave_the_scale_error_of_an_axis_analytically() {
        // M = diag(1.01, 1, 1) kept as offsets only: the error is (1/1.01 - 1) u_x, rms over the sphere
        // |1/1.01 - 1| / sqrt(3), worst |1/1.01 - 1|.
        let scale_error = 1.0 - 1.0 / 1.01;
        let (rms, worst) = spread(&diagonal([1.01, 1.0, 1.0]), &O, &diagonal([1.0; 3]), &O);
        assert!((rms / (scale_error / 3f64.sqrt()) - 1.0).abs() < 1e-3, "rms {rms}");
        assert!((worst / scale_error - 1.0).abs() < 1e-3, "worst {worst}");
        assert!(spread(&M, &O, &M, &O).1 < 1e-15, "the full calibration loses nothing");
    }

    #[test]
    fn best_diagonal_leaves_less_than_the_matrix_diagonal_or_any_nudge_of_it() {
        let best = best_diagonal(&M);
        let rms = |scale: Vec3<f64>| spread(&M, &O, &diagonal(scale), &O).0;
        let at_best = rms(best);
        assert!(at_best < rms([M[0][0], M[1][1], M[2][2]]), "the diagonal of M is not the best per-axis scale here");
        for axis in 0..3 {
            for nudge in [-1e-4, 1e-4] {
                let mut scale = best;
                scale[axis] += nudge;
                assert!(rms(scale) > at_best, "axis {axis} nudged by {nudge} leaves less");
            }
        }
    }
}
