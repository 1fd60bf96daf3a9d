//! The calibration data file of DESIGN.md: a CSV with a header row, one averaged reading per row.
//!
//! Columns: `x,y,z` the averaged reading in any unit; optional `ref_x,ref_y,ref_z` the known specific
//! force in output units (cells empty where the orientation is unknown); optional capture statistics
//! `count`, `std_x,std_y,std_z` (in the reading's unit), `temp_c` and `gyro_x_dps,gyro_y_dps,gyro_z_dps`;
//! any other columns are accepted and ignored. The published data sets' own headers are accepted too:
//! `mx,my,mz` or `raw_x,raw_y,raw_z` for the reading, and `incl_deg,toolface_deg` (data/README.md) for
//! a known orientation.

mod columns;
mod read;
mod rows;
mod write;

use crate::limits::{REPEAT_FRACTION, SAMPLE_FILE_ROWS};
pub use rows::{parse_row_list, RowList};
pub use write::csv_text;

/// One averaged reading and what the file says about it.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Row {
    /// Line number in the file (the header is line 1).
    pub line: usize,
    /// Averaged reading, in the file's unit.
    pub reading: [f64; 3],
    /// Known specific force in output units, when the orientation is known.
    pub reference: Option<[f64; 3]>,
    /// Samples averaged into the reading (`count`).
    pub count: Option<u32>,
    /// Standard deviation of the samples per axis, in the reading's unit (`std_x,std_y,std_z`).
    pub std: Option<[f64; 3]>,
    /// Mean die temperature during the capture, in degC (`temp_c`).
    pub temp_c: Option<f64>,
    /// Mean gyro reading per axis, in deg/s (`gyro_x_dps,gyro_y_dps,gyro_z_dps`).
    pub gyro_mean_dps: Option<[f64; 3]>,
}

impl Row {
    /// A row with a reading and, when known, its reference; no capture statistics.
    pub fn new(line: usize, reading: [f64; 3], reference: Option<[f64; 3]>) -> Self {
        Row { line, reading, reference, ..Row::default() }
    }
}

/// A whole calibration data file.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Dataset {
    /// The rows, in file order.
    pub rows: Vec<Row>,
}

impl Dataset {
    /// Whether the rows are single samples rather than averaged positions: no row says how many
    /// samples it averages, and most follow one that reads about the same (a resting board printed
    /// over and over, not one row per position).
    pub fn looks_like_samples(&self) -> bool {
        if self.rows.len() < SAMPLE_FILE_ROWS || self.rows.iter().any(|r| r.count.is_some()) {
            return false;
        }
        let size = |r: [f64; 3]| shared::linalg::norm(r);
        let close = |pair: &[Row]| {
            size(shared::linalg::sub(pair[1].reading, pair[0].reading)) < REPEAT_FRACTION * size(pair[0].reading)
        };
        let repeats = self.rows.windows(2).filter(|pair| close(pair)).count();
        2 * repeats >= self.rows.len()
    }

    /// The median size of the rows' references when it is gravity's in m/s^2 (9.81, an imucal data
    /// set's) and not `g`: a fit to them with `g` misses by their difference (8810 mg at `g` 1).
    pub fn references_in_ms2(&self, g: f64) -> Option<f64> {
        let mut sizes: Vec<f64> = self.references().map(|(_, r)| shared::linalg::norm(r)).collect();
        sizes.sort_by(f64::total_cmp);
        let median = *sizes.get(sizes.len() / 2)?;
        let near = |a: f64, b: f64| (a / b - 1.0).abs() <= REFERENCE_SIZE_TOLERANCE;
        (near(median, shared::STANDARD_GRAVITY) && !near(median, g)).then_some(median)
    }

    /// The rows whose orientation is known.
    pub fn references(&self) -> impl Iterator<Item = (&Row, [f64; 3])> {
        self.rows.iter().filter_map(|row| row.reference.map(|r| (row, r)))
    }
}

/// How far the references' median size may be from a gravity's and count as it.
///
/// NOTE: references are directions scaled by a local g (9.78-9.83 m/s^2 on Earth's surface) or by
/// 9.81; 5 % takes them all and leaves 1 g and 9.81 twice a decade apart.
const REFERENCE_SIZE_TOLERANCE: f64 = 0.05;

/// Why a data file was refused; every variant names the line.
#[derive(Debug, thiserror::Error)]
pub enum DataError {
    #[error("cannot read {path}: {source}")]
    Io { path: String, source: std::io::Error },
    #[error("line 1: no reading columns: expected x,y,z (or mx,my,mz, or raw_x,raw_y,raw_z); the header has {found}")]
    MissingColumns { found: String },
    #[error("line 1: the header has {found} but not all of {expected}; give all of them or none")]
    PartialColumns { found: String, expected: String },
    #[error("line {line}, column {column}: {value:?} is not a number")]
    NotANumber { line: usize, column: String, value: String },
    #[error("line {line}, column {column}: {value:?} is not a sample count")]
    NotACount { line: usize, column: String, value: String },
    #[error("line {line}, column {column}: the reading is empty")]
    EmptyReading { line: usize, column: String },
    #[error("line {line}: the {group} is only partly given; fill all of its cells or leave them all empty")]
    PartlyGiven { line: usize, group: &'static str },
    #[error("line {line}: {reason}")]
    BadRow { line: usize, reason: String },
    #[error("the file has a header but no data rows; add one averaged reading per line")]
    NoRows,
}
