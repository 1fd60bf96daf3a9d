//! Writing a data file that [`Dataset::from_path`] reads back: the reading and the capture
//! statistics, and a last column of labels.

use std::fmt::Write as _;

use super::columns;
use super::{Dataset, Row};

impl Dataset {
    /// The rows as CSV with the capture-statistics columns and a last column `label_column` holding
    /// `labels` (commas in a label become spaces).
    pub fn to_csv(&self, label_column: &str, labels: &[&str]) -> String {
        let mut out = header(label_column);
        for (row, label) in self.rows.iter().zip(labels) {
            let _ = writeln!(out, "{},{}", cells(row).join(","), label.replace(',', " "));
        }
        out
    }
}

fn header(label_column: &str) -> String {
    let mut names: Vec<&str> = columns::READING[0].to_vec();
    names.push(columns::COUNT);
    names.extend(columns::STD);
    names.push(columns::TEMP);
    names.extend(columns::GYRO);
    names.push(label_column);
    names.join(",") + "\n"
}

/// The row's cells, empty where a value is absent.
fn cells(row: &Row) -> Vec<String> {
    let three = |v: Option<[f64; 3]>| v.map_or([None; 3], |v| v.map(Some));
    let mut cells: Vec<Option<String>> = row.reading.iter().map(|v| Some(v.to_string())).collect();
    cells.push(row.count.map(|c| c.to_string()));
    cells.extend(three(row.std).map(|v| v.map(|v| v.to_string())));
    cells.push(row.temp_c.map(|t| t.to_string()));
    cells.extend(three(row.gyro_mean_dps).map(|v| v.map(|v| v.to_string())));
    cells.into_iter().map(Option::unwrap_or_default).collect()
}
