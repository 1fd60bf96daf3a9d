//! Standard errors that hold whether the residual scatter comes from the sensor's noise or from what
//! the model misses: one from the residual scatter (s^2 (J^T J)^-1), one from the noise the captures
//! measured (the sandwich (J^T J)^-1 J^T V J (J^T J)^-1 with V the covariance of the residuals that
//! noise alone gives; fit/covariance.rs for the least-squares models). The noise's is reported, scaled up by sqrt(chi-square / dof) when the
//! residuals are significantly larger than that noise explains (something the model misses adds to
//! them); the scatter's only where the file gives no noise.
//!
//! NOTE: not the scatter's whenever it is larger: with rows of 2 to 3000 samples the noise differs
//! a thousandfold between rows, and s^2 (J^T J)^-1, which assumes one noise for all, overstated some
//! errors 4-fold and understated others (tests/uncertainty_monte_carlo.rs prints both).

use nalgebra::{DMatrix, Matrix4, Vector3};

use crate::data::Dataset;
use crate::limits::SCATTER_SIGNIFICANCE;
use crate::limits::TRUSTED_SAMPLE_COUNT;
use statrs::distribution::{ChiSquared, ContinuousCDF};

/// The variance of one sample per axis, in the file's unit squared, pooled over every row that
/// carries `count` and `std_*`: sum (n_i - 1) s_i^2 / sum (n_i - 1).
///
/// NOTE: pooled rather than row by row: the noise is the sensor's, the same in every still capture,
/// and a row of two samples measures its own spread to within 100 % (one degree of freedom), which
/// would make that row's weight a coin toss. `None` unless every row carries both.
pub(super) fn pooled_sample_variance(dataset: &Dataset) -> Option<Vector3<f64>> {
    let (mut sum, mut degrees) = (Vector3::zeros(), 0.0);
    for row in &dataset.rows {
        let (count, std) = (f64::from(row.count?), Vector3::from(row.std?));
        sum += std.component_mul(&std) * (count - 1.0).max(0.0);
        degrees += (count - 1.0).max(0.0);
    }
    (degrees > 0.0 && sum.iter().all(|v| v.is_finite() && *v > 0.0)).then(|| sum / degrees)
}

/// The factor by which the noise-based errors are scaled: sqrt(chi-square / dof) when the
/// residuals exceed the noise significantly, else 1.
///
/// NOTE: a chi-square at or below its degrees of freedom (its mean) is never significant at 5 %: its
/// tail beyond the mean is 0.32 for one degree of freedom and grows towards one half, so the tail
/// probability (a series statrs sums for every fit) is computed only above it.
pub(super) fn inflation(chi_square: f64, degrees_of_freedom: usize) -> f64 {
    if chi_square <= degrees_of_freedom as f64 {
        return 1.0;
    }
    let Ok(distribution) = ChiSquared::new(degrees_of_freedom as f64) else {
        return 1.0;
    };
    if distribution.sf(chi_square) < SCATTER_SIGNIFICANCE {
        (chi_square / degrees_of_freedom as f64).sqrt()
    } else {
        1.0
    }
}

/// For each reading axis c, the covariance of the linear solution's column c, (A^T A)^-1 A^T W_c A
/// (A^T A)^-1 with W_c = diag(sigma_c^2 f_i), for rows `design` (a^T 1), where the noise (per-sample
/// variance sigma^2 per axis and each row's factor f_i: its weight over its count) is known; with the
/// factor for what the `residuals` (row i, axis c) show beyond that noise.
pub(super) fn linear_noise_errors(
    design: &DMatrix<f64>,
    inverse_normal: &Matrix4<f64>,
    residuals: &DMatrix<f64>,
    noise: Option<(Vector3<f64>, Vec<f64>)>,
) -> (Option<[Matrix4<f64>; 3]>, f64) {
    let Some((per_sample, factors)) = noise else {
        return (None, 1.0);
    };
    let chi_square = linear_chi_square(residuals, &factors, &per_sample);
    let covariances = [0, 1, 2].map(|c| {
        let mut middle = Matrix4::zeros();
        for (i, factor) in factors.iter().enumerate() {
            let a = design.row(i).transpose().fixed_rows::<4>(0).into_owned();
            middle += a * a.transpose() * (per_sample[c] * factor);
        }
        inverse_normal * middle * inverse_normal
    });
    let degrees_of_freedom = 3 * factors.len().saturating_sub(design.ncols());
    (Some(covariances), inflation(chi_square, degrees_of_freedom))
}

/// Sum over rows i and axes c of r_ic^2 / (f_i sigma_c^2).
fn linear_chi_square(residuals: &DMatrix<f64>, factors: &[f64], per_sample: &Vector3<f64>) -> f64 {
    let row = |i: usize| (0..3).map(|c| residuals[(i, c)].powi(2) / (factors[i] * per_sample[c])).sum::<f64>();
    (0..factors.len()).map(row).sum()
}

/// Each row's weight in the fit, relative to the mean: its sample count where every row carries its
/// count and the data its noise (the variance of a row's mean is the sensor's over its count), else 1.
///
/// NOTE: one noise for all rows (pooled, as in [`pooled_sample_variance`]), so only the count weighs:
/// rows of 2 and of 3000 samples differ 1500-fold in variance, and an unweighted fit lets the short
/// rows' noise into every parameter.
pub(super) fn row_weights(dataset: &Dataset) -> Vec<f64> {
    // NOTE: checked before collecting: a collect into Option<Vec> cannot know its length and grew
    // the vector three times per fit.
    if dataset.rows.iter().all(|r| r.count.is_some()) && pooled_sample_variance(dataset).is_some() {
        let counts: Vec<f64> = dataset.rows.iter().map(|r| r.count.map_or(0.0, f64::from)).collect();
        relative_weights(&counts)
    } else {
        vec![1.0; dataset.rows.len()]
    }
}

/// Sample counts relative to their mean (exactly 1 when all are equal).
pub(super) fn relative_weights(counts: &[f64]) -> Vec<f64> {
    let mean = counts.iter().sum::<f64>() / counts.len() as f64;
    counts.iter().map(|n| if mean > 0.0 { n / mean } else { 1.0 }).collect()
}

/// The warnings about too little redundancy or too short captures, where they apply.
pub(super) fn redundancy_warnings(training: &Dataset, degrees_of_freedom: usize) -> Vec<String> {
    let few = (degrees_of_freedom <= 2).then(|| {
        format!(
            "only {degrees_of_freedom} residual degree(s) of freedom: the residual scatter says little about \
             the error; the standard errors lean on the measured noise (add positions for a check)"
        )
    });
    few.into_iter().chain(short_rows_warning(training)).collect()
}

/// The warning naming the rows that averaged fewer than [`TRUSTED_SAMPLE_COUNT`] samples.
fn short_rows_warning(training: &Dataset) -> Option<String> {
    let short = training.rows.iter().filter(|r| r.count.is_some_and(|n| n < TRUSTED_SAMPLE_COUNT));
    let lines: Vec<String> = short.map(|r| r.line.to_string()).collect();
    (!lines.is_empty()).then(|| {
        format!(
            "line(s) {} averaged fewer than {TRUSTED_SAMPLE_COUNT} samples: their spread is a rough guess \
             of the noise; capture longer",
            lines.join(", ")
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_chi_square_at_or_below_its_mean_is_never_significant_so_the_shortcut_changes_nothing() {
        for dof in (1..=200).chain([500, 1000, 5000, 20000]) {
            let k = dof as f64;
            let tail = ChiSquared::new(k).unwrap().sf(k);
            assert!(tail > 0.3 && tail < 0.5, "{dof} degrees of freedom: tail beyond the mean {tail}");
            for ratio in [0.0, 0.5, 0.99, 1.0, 1.01, 1.2, 1.5, 2.0, 3.0] {
                let chi_square = ratio * k;
                let significant = ChiSquared::new(k).unwrap().sf(chi_square) < SCATTER_SIGNIFICANCE;
                let expected = if significant { (chi_square / k).sqrt() } else { 1.0 };
                assert_eq!(inflation(chi_square, dof), expected, "{dof} degrees of freedom, chi-square {chi_square}");
            }
        }
    }
}
