//! What residuals larger than the capture noise point to, with figures: a board that moved during a
//! capture, known orientations placed a few degrees off, noise of long averages below any real
//! model's floor, or a model too simple for the sensor.

use nalgebra::{Matrix3, Vector3};

use super::uncertainty::pooled_sample_variance;
use super::NoiseTest;
use crate::data::{Dataset, Row};
use crate::limits::{MODEL_FLOOR_MG, MOVED_STD_RATIO, PLACEMENT_DEG};

/// The residuals' figures, in mg and degrees.
struct Figures {
    /// RMS of | |a| - g | over the rows.
    residual_mg: f64,
    /// RMS of the noise of | |a| | the rows' sample counts and the pooled noise predict.
    noise_mg: f64,
    /// RMS angle between a and the known orientation over the rows that have one.
    placement_deg: Option<f64>,
    /// Lines whose sample spread is far above the others'.
    moved_lines: Vec<usize>,
}

/// The warning for a failed noise test: the statistic, then what the evidence points to.
pub(super) fn noise_warning(
    training: &Dataset,
    matrix: &Matrix3<f64>,
    offset: &Vector3<f64>,
    g: f64,
    test: &NoiseTest,
) -> String {
    let head = format!(
        "the residuals exceed what the capture noise explains (chi-square {:.1} on {} degrees of freedom, p = {:.1e})",
        test.chi_square, test.degrees_of_freedom, test.p_value
    );
    format!("{head}: {}", explanation(&figures(training, matrix, offset, g)))
}

fn explanation(f: &Figures) -> String {
    let (residual, noise) = (f.residual_mg, f.noise_mg);
    if !f.moved_lines.is_empty() {
        return moved_text(&f.moved_lines);
    }
    if let Some(angle) = f.placement_deg.filter(|&a| a > PLACEMENT_DEG) {
        return format!(
            "the known orientations are placed about {angle:.2} degrees off (RMS angle between a and ref), \
             while | |a| - g | is {residual:.3} mg RMS; fit without them (ortho9) or place them more exactly"
        );
    }
    if residual < MODEL_FLOOR_MG {
        return format!(
            "the noise of long averages ({noise:.4} mg RMS) is below any real model's floor ({MODEL_FLOOR_MG} mg): \
             the residuals, {residual:.3} mg RMS, are small; nothing to fix"
        );
    }
    format!(
        "the model is too simple for the sensor: | |a| - g | is {residual:.3} mg RMS against {noise:.4} mg of noise; \
         try a richer model, or the board moved between captures"
    )
}

fn moved_text(lines: &[usize]) -> String {
    let lines = lines.iter().map(ToString::to_string).collect::<Vec<_>>().join(", ");
    format!("the board moved: line(s) {lines} scatter over {MOVED_STD_RATIO} times the others; capture them again")
}

fn figures(training: &Dataset, matrix: &Matrix3<f64>, offset: &Vector3<f64>, g: f64) -> Figures {
    let variance = pooled_sample_variance(training).unwrap_or_default();
    let mg = 1000.0 / g;
    let (mut residual, mut noise, mut angles) = (0.0, 0.0, Vec::new());
    for row in &training.rows {
        let a = matrix * (Vector3::from(row.reading) - offset);
        residual += ((a.norm() - g) * mg).powi(2);
        noise += norm_noise_variance(row, matrix, &a, &variance) * mg * mg;
        angles.extend(row.reference.map(|r| a.angle(&Vector3::from(r)).to_degrees().powi(2)));
    }
    let n = training.rows.len().max(1) as f64;
    let placement_deg = (!angles.is_empty()).then(|| (angles.iter().sum::<f64>() / angles.len() as f64).sqrt());
    Figures {
        residual_mg: (residual / n).sqrt(),
        noise_mg: (noise / n).sqrt(),
        placement_deg,
        moved_lines: moved(training, &variance),
    }
}

/// The variance of |a| a row's mean carries from the pooled per-sample `variance`.
fn norm_noise_variance(row: &Row, matrix: &Matrix3<f64>, a: &Vector3<f64>, variance: &Vector3<f64>) -> f64 {
    let direction = a / a.norm();
    let per_mean = Matrix3::from_diagonal(&(variance / f64::from(row.count.unwrap_or(1).max(1))));
    (direction.transpose() * matrix * per_mean * matrix.transpose() * direction)[0]
}

/// Lines whose largest per-axis spread exceeds the pooled spread by [`MOVED_STD_RATIO`].
fn moved(training: &Dataset, variance: &Vector3<f64>) -> Vec<usize> {
    let pooled = variance.map(f64::sqrt);
    training
        .rows
        .iter()
        .filter(|r| r.std.is_some_and(|s| (0..3).any(|k| s[k] > MOVED_STD_RATIO * pooled[k])))
        .map(|r| r.line)
        .collect()
}
