//! Statistics of a fit: the residuals against the noise the captures measured, and the placement
//! misalignment the 9- versus 12-parameter difference reveals.

use nalgebra::{Matrix3, Vector3};
use serde::Serialize;
use shared::linalg::Mat3;
use statrs::distribution::{ChiSquared, ContinuousCDF};

use super::normalization::Normalization;
use crate::data::Row;
use crate::limits::NOISE_TEST_LEVEL;

/// The residuals of a fit tested against the noise of the averaged readings.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct NoiseTest {
    /// Sum of squared residuals, each divided by the standard deviation the captures predict.
    pub chi_square: f64,
    /// Residuals minus parameters.
    pub degrees_of_freedom: usize,
    /// Probability of a chi-square at least this large if the residuals were noise alone.
    pub p_value: f64,
    /// Whether the residuals are consistent with the noise (p >= 0.001).
    pub passed: bool,
}

impl NoiseTest {
    /// The test in words, with the levels it is read at: consistent at the 5 % level the standard
    /// errors use, larger at 5 % (the standard errors are scaled up for it), or larger at 0.1 %.
    pub fn verdict(&self) -> String {
        let (chi, dof, p) = (self.chi_square, self.degrees_of_freedom, self.p_value);
        let test = format!("chi-square {chi:.1} on {dof} degrees of freedom, p = {p:.3}");
        if !self.passed {
            format!("residuals larger than the capture noise: {test}, below the 0.1 % level")
        } else if p < crate::limits::SCATTER_SIGNIFICANCE {
            format!(
                "residuals larger than the capture noise at the 5 % level (the standard errors are scaled up for \
                 it), not at 0.1 %: {test}"
            )
        } else {
            format!("residuals consistent with the capture noise at the 5 % level: {test}")
        }
    }
}

/// The chi-square test of the residuals, from their chi-square against the noise every row states
/// (`count` and `std_x,std_y,std_z`, in the file's unit; `None` when a row does not), with
/// `residuals` - `parameters` degrees of freedom; `None` without redundancy.
pub(super) fn noise_test(chi_square: Option<f64>, residuals: usize, parameters: usize) -> Option<NoiseTest> {
    let chi_square = chi_square?;
    let degrees_of_freedom = residuals.checked_sub(parameters).filter(|&d| d > 0)?;
    let p_value = ChiSquared::new(degrees_of_freedom as f64).ok()?.sf(chi_square);
    Some(NoiseTest { chi_square, degrees_of_freedom, p_value, passed: p_value >= NOISE_TEST_LEVEL })
}

/// The variance of a row's mean, per axis, in the solver's units: std^2 / (count r^2).
///
/// NOTE: as a variance, not a standard deviation squared afterwards: a square root and two divisions
/// in a row were the longest chain of the statistics pass (issue 29).
pub(super) fn normalised_variance_of_mean(row: &Row, normalization: &Normalization) -> Option<Vector3<f64>> {
    let (count, std, radii) = (f64::from(row.count?), row.std?, normalization.radii);
    let variance = Vector3::from_fn(|k, _| std[k] * std[k] / (count * (radii[k] * radii[k])));
    (count >= 1.0 && variance.iter().all(|v| v.is_finite() && *v > 0.0)).then_some(variance)
}

/// One row's share of chi-square: its three residuals a - ref over their variances, or (a norm row,
/// `along` its [`variance_along`] vector) its one residual over its variance; the residuals are
/// those of a reading with per-axis `variances` corrected by `matrix`.
pub(super) fn chi_square_term(
    residuals: &Vector3<f64>,
    along: Option<Vector3<f64>>,
    matrix: &Matrix3<f64>,
    variances: &Vector3<f64>,
) -> f64 {
    match along {
        None => {
            let axis_variances = matrix.component_mul(matrix) * variances;
            (0..3).map(|k| residuals[k].powi(2) / axis_variances[k]).sum()
        }
        Some(along) => residuals[0].powi(2) / variance_along(&along, variances),
    }
}

/// The variance along the unit vector d of M times a reading with per-axis `variances`,
/// d^T M diag(v) M^T d, as the sum of v_k (M^T d)_k^2; `along` is M^T d.
pub(super) fn variance_along(along: &Vector3<f64>, variances: &Vector3<f64>) -> f64 {
    along.component_mul(along).dot(variances)
}

/// The rotation, in degrees, between a 12-parameter fit (which knows the orientations) and a
/// 9-parameter fit (which cannot see a rotation): M12 M9^-1 is close to the rotation by which the
/// positions were misplaced; its nearest rotation's angle estimates that misalignment.
pub fn misalignment_deg(full: &Mat3<f64>, triangular: &Mat3<f64>) -> Option<f64> {
    let full = Matrix3::from_fn(|i, j| full[i][j]);
    let triangular = Matrix3::from_fn(|i, j| triangular[i][j]);
    let relative = full * triangular.try_inverse()?;
    let svd = relative.svd(true, true);
    let rotation = svd.u? * svd.v_t?;
    let cosine = ((rotation.trace() - 1.0) / 2.0).clamp(-1.0, 1.0);
    Some(cosine.acos().to_degrees())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_p_value_between_the_levels_is_not_called_consistent() {
        let test = |p_value: f64| NoiseTest {
            chi_square: 9.0,
            degrees_of_freedom: 3,
            p_value,
            passed: p_value >= NOISE_TEST_LEVEL,
        };
        assert!(test(0.003).verdict().starts_with("residuals larger than the capture noise at the 5 % level"));
        assert!(test(0.2).verdict().starts_with("residuals consistent with the capture noise at the 5 % level"));
        assert!(test(0.0001).verdict().contains("below the 0.1 % level"));
    }
    use nalgebra::{Rotation3, Unit};

    #[test]
    fn misalignment_recovers_a_known_rotation() {
        let triangular =
            Matrix3::new(1.0006, 3.58e-4 * 1.003, -7.29e-3 * 0.9834, 0.0, 1.003, 4.62e-4 * 0.9834, 0.0, 0.0, 0.9834);
        let axis = Unit::new_normalize(Vector3::new(0.3, -0.5, 0.8));
        let rotation = Rotation3::from_axis_angle(&axis, 1.5f64.to_radians());
        let full = rotation.matrix() * triangular;
        let to_array = |m: Matrix3<f64>| [0, 1, 2].map(|i| [0, 1, 2].map(|j| m[(i, j)]));
        let angle = misalignment_deg(&to_array(full), &to_array(triangular)).unwrap();
        assert!((angle - 1.5).abs() < 1e-9, "{angle}");
    }
}
