//! The record a session uploaded to the board, as its report shows it: the chip's own values (f32,
//! the gyro's G included), and each position calibrated as the chip calibrates it.

use std::fmt::Write;

use serde::Serialize;
use shared::{linalg, Calibration};

use super::html::fixed_cell;
use crate::calibration::{self, CalibrationJson};
use crate::session::Session;

/// The uploaded record: one line, and every value as `download` would print it.
#[derive(Debug, Clone, Serialize)]
pub struct Uploaded {
    /// The record in one line (model, scale, offset, residual, gyro, temperature model).
    pub line: String,
    /// The record's values (M, o, gyro G and bias, temperature model).
    pub record: CalibrationJson,
}

impl Uploaded {
    /// The report's view of `record`.
    pub fn of(record: &Calibration) -> Self {
        Uploaded { line: calibration::describe(record), record: CalibrationJson::from_device(record) }
    }
}

/// Each capture's mean as the chip calibrates it with `record` at the capture's die temperature, in g.
pub fn calibrated_by(record: &Calibration, session: &Session) -> Vec<[f64; 3]> {
    let calibrate = |mean_g: [f32; 3], temp_c: f32| {
        let (matrix, offset) = calibration::applied_at(record, temp_c);
        linalg::mul_vec(&matrix, linalg::sub(mean_g.map(f64::from), offset))
    };
    session
        .captures
        .iter()
        .map(|c| {
            calibrate(
                c.stats.mean_g,
                mutant!("uploaded-first-temperature", c.stats.temp_c, session.captures[0].stats.temp_c),
            )
        })
        .collect()
}

/// The uploaded record's section of the HTML page: its line, then M, o and G row by row, each number
/// with its JSON pointer.
pub fn html_section(out: &mut String, uploaded: Option<&Uploaded>) {
    let Some(uploaded) = uploaded else {
        return;
    };
    let _ = write!(out, "<section><h2>Uploaded to the board</h2><p>{}</p>", crate::shown::escape(&uploaded.line));
    out.push_str("<div class=\"table-wrap\"><table><tr><th>row</th><th colspan=\"3\">M</th><th>o (g)</th>");
    out.push_str("<th colspan=\"3\">gyro G</th></tr>");
    for i in 0..3 {
        let _ = write!(out, "<tr><td>{i}</td>");
        let record = &uploaded.record;
        for (j, value) in record.matrix[i].iter().enumerate() {
            out.push_str(&fixed_cell(&format!("/uploaded/record/matrix/{i}/{j}"), Some(*value), 6));
        }
        out.push_str(&fixed_cell(&format!("/uploaded/record/offset/{i}"), Some(record.offset[i]), 6));
        for j in 0..3 {
            let g = record.gyro_matrix.map(|g| g[i][j]);
            out.push_str(&fixed_cell(&format!("/uploaded/record/gyro_matrix/{i}/{j}"), g, 6));
        }
        out.push_str("</tr>");
    }
    out.push_str("</table></div></section>");
}
