//! Errors of a data set before and after a calibration: | |a| - g | on every row; |a - ref| and the
//! inclination and toolface errors (data/README.md) where the orientation is known.

use serde::Serialize;
use shared::linalg::{self, Mat3, Vec3};
use shared::orientation::{inclination_deg, toolface_deg};

use crate::data::{Dataset, Row};
use crate::limits::TOOLFACE_UNDEFINED_ABOVE_DEG;

/// The errors of one row, in output units and degrees.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RowEvaluation {
    /// Line in the data file.
    pub line: usize,
    /// Whether the fit used this row (a training row) or not (a test row).
    pub training: bool,
    /// | |m| - g | of the uncorrected reading.
    pub norm_error_before: f64,
    /// | |a| - g | of the corrected reading.
    pub norm_error_after: f64,
    /// |m - ref| of the uncorrected reading, where the orientation is known.
    pub reference_error_before: Option<f64>,
    /// |a - ref| of the corrected reading, where the orientation is known.
    pub reference_error_after: Option<f64>,
    /// Inclination of the corrected reading minus the known inclination, in degrees.
    pub inclination_error_deg: Option<f64>,
    /// Toolface of the corrected reading minus the known toolface, in degrees, wrapped to +-180;
    /// `None` where toolface is undefined (inclination near +-90 degrees).
    pub toolface_error_deg: Option<f64>,
}

/// The errors of every row.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Evaluation {
    /// One entry per row of the data set.
    pub rows: Vec<RowEvaluation>,
    /// Whether the "before" errors are of readings put on a nominal scale (the file's readings are not
    /// in the output unit: centred on the ellipsoid through them and scaled by its mean radius to g).
    pub before_nominal: bool,
}

/// Errors of every row, before (a = m) and after (a = M (m - o)) the calibration; rows on
/// `training_lines` are marked as training rows.
pub fn evaluate(
    dataset: &Dataset,
    matrix: &Mat3<f64>,
    offset: &Vec3<f64>,
    g: f64,
    training_lines: &[usize],
) -> Evaluation {
    let nominal = nominal_scale(dataset, g);
    let training: std::collections::HashSet<usize> = training_lines.iter().copied().collect();
    let rows = dataset
        .rows
        .iter()
        .map(|row| {
            let corrected = linalg::mul_vec(matrix, linalg::sub(row.reading, *offset));
            let before = nominal.map_or(row.reading, |(c, s)| linalg::scale(linalg::sub(row.reading, c), s));
            evaluate_row(row, before, corrected, g, training.contains(&row.line))
        })
        .collect();
    Evaluation { rows, before_nominal: nominal.is_some() }
}

/// For readings not in the output unit (median |m| off g by more than a factor of two): the centre
/// of the ellipsoid through them and the factor that takes its mean radius to g.
///
/// NOTE: "before" in mg must be mg: raw counts compared with g as they stand give errors of millions.
fn nominal_scale(dataset: &Dataset, g: f64) -> Option<(Vec3<f64>, f64)> {
    let mut norms: Vec<f64> = dataset.rows.iter().map(|r| linalg::norm(r.reading) / g).collect();
    norms.sort_by(f64::total_cmp);
    let median = *norms.get(norms.len() / 2)?;
    if (0.5..=2.0).contains(&median) {
        return None;
    }
    let ellipsoid = super::normalization::Normalization::of_dataset(dataset);
    let radius = ellipsoid.radii.iter().product::<f64>().cbrt();
    (radius > 0.0).then(|| (ellipsoid.center, g / radius))
}

/// The errors of one row with its reading `before` and after correction.
fn evaluate_row(row: &Row, before: Vec3<f64>, corrected: Vec3<f64>, g: f64, training: bool) -> RowEvaluation {
    let distance = |a: Vec3<f64>| row.reference.map(|r| linalg::norm(linalg::sub(a, r)));
    let inclination_error_deg = row.reference.map(|r| inclination_deg(corrected) - inclination_deg(r));
    let toolface_error_deg = row
        .reference
        .filter(|r| inclination_deg(*r).abs() < TOOLFACE_UNDEFINED_ABOVE_DEG)
        .map(|r| wrap_deg(toolface_deg(corrected) - toolface_deg(r)));
    RowEvaluation {
        line: row.line,
        training,
        norm_error_before: (linalg::norm(before) - g).abs(),
        norm_error_after: (linalg::norm(corrected) - g).abs(),
        reference_error_before: distance(before),
        reference_error_after: distance(corrected),
        inclination_error_deg,
        toolface_error_deg,
    }
}

/// An angle difference wrapped to (-180, 180].
fn wrap_deg(angle: f64) -> f64 {
    let wrapped = angle.rem_euclid(360.0);
    if wrapped > 180.0 {
        wrapped - 360.0
    } else {
        wrapped
    }
}

impl Evaluation {
    /// Largest | |a| - g | before and after, over all rows.
    pub fn worst_norm_error(&self) -> (f64, f64) {
        self.worst(|r| Some((r.norm_error_before, r.norm_error_after)))
    }

    /// Largest |a - ref| before and after over the rows of known orientation; `None` without any.
    pub fn worst_reference_error(&self) -> Option<(f64, f64)> {
        self.rows
            .iter()
            .any(|r| r.reference_error_before.is_some())
            .then(|| self.worst(|r| r.reference_error_before.zip(r.reference_error_after)))
    }

    /// RMS of | |a| - g | after calibration over the training or the test rows; `None` without any.
    pub fn rms_norm_error(&self, training: bool) -> Option<f64> {
        let errors: Vec<f64> =
            self.rows.iter().filter(|r| r.training == training).map(|r| r.norm_error_after).collect();
        (!errors.is_empty()).then(|| (errors.iter().map(|e| e * e).sum::<f64>() / errors.len() as f64).sqrt())
    }

    fn worst(&self, pick: impl Fn(&RowEvaluation) -> Option<(f64, f64)>) -> (f64, f64) {
        self.rows.iter().filter_map(pick).fold((0.0, 0.0), |(b, a), (rb, ra)| (b.max(rb), a.max(ra)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn toolface_differences_wrap_across_north() {
        assert_eq!(wrap_deg(359.0 - 1.0), -2.0);
        assert_eq!(wrap_deg(1.0 - 359.0), 2.0);
        assert_eq!(wrap_deg(-90.0), -90.0);
    }
}
