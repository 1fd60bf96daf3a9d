//! Errors of a data set before and after a calibration: | |a| - g | on every row, |a - ref| where the
//! orientation is known.

use serde::Serialize;
use shared::linalg::{self, Mat3, Vec3};

use crate::data::Dataset;

/// The errors of one row, in output units.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RowEvaluation {
    /// Line in the data file.
    pub line: usize,
    /// | |m| - g | of the uncorrected reading.
    pub norm_error_before: f64,
    /// | |a| - g | of the corrected reading.
    pub norm_error_after: f64,
    /// |m - ref| of the uncorrected reading, where the orientation is known.
    pub reference_error_before: Option<f64>,
    /// |a - ref| of the corrected reading, where the orientation is known.
    pub reference_error_after: Option<f64>,
}

/// The errors of every row.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Evaluation {
    /// One entry per row of the data set.
    pub rows: Vec<RowEvaluation>,
}

/// Errors of every row, before (a = m) and after (a = M (m - o)) the calibration.
pub fn evaluate(dataset: &Dataset, matrix: &Mat3<f64>, offset: &Vec3<f64>, g: f64) -> Evaluation {
    let rows = dataset
        .rows
        .iter()
        .map(|row| {
            let corrected = linalg::mul_vec(matrix, linalg::sub(row.reading, *offset));
            let distance = |a: Vec3<f64>| row.reference.map(|r| linalg::norm(linalg::sub(a, r)));
            RowEvaluation {
                line: row.line,
                norm_error_before: (linalg::norm(row.reading) - g).abs(),
                norm_error_after: (linalg::norm(corrected) - g).abs(),
                reference_error_before: distance(row.reading),
                reference_error_after: distance(corrected),
            }
        })
        .collect();
    Evaluation { rows }
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

    fn worst(&self, pick: impl Fn(&RowEvaluation) -> Option<(f64, f64)>) -> (f64, f64) {
        self.rows.iter().filter_map(pick).fold((0.0, 0.0), |(b, a), (rb, ra)| (b.max(rb), a.max(ra)))
    }
}
