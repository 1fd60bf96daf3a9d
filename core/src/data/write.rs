//! Writing a data file that [`Dataset::from_path`] reads back: the reading and the capture
//! statistics, and a last column of labels.

use super::columns;
use super::{Dataset, Row};

impl Dataset {
    /// The rows as CSV with the capture-statistics columns and a last column `label_column` holding
    /// `labels` (commas in a label become spaces, so that the file splits on every comma).
    pub fn to_csv(&self, label_column: &str, labels: &[&str]) -> String {
        let header = header(label_column).into_iter().map(str::to_owned).collect();
        let rows =
            self.rows.iter().zip(labels).map(|(row, label)| [cells(row), vec![label.replace(',', " ")]].concat());
        csv_text(std::iter::once(header).chain(rows))
    }
}

/// Records as CSV text, written by the csv crate (quoted only where a cell needs it), one per line.
pub fn csv_text(records: impl IntoIterator<Item = Vec<String>>) -> String {
    let mut writer = csv::Writer::from_writer(Vec::new());
    // NOTE: a csv writer into memory cannot fail (its only errors are the sink's), and every cell is
    // UTF-8 text, so none of the results below can be an error.
    records.into_iter().for_each(|record| drop(writer.write_record(&record)));
    String::from_utf8(writer.into_inner().unwrap_or_default()).unwrap_or_default()
}

fn header(label_column: &str) -> Vec<&str> {
    let mut names: Vec<&str> = columns::READING[0].to_vec();
    names.push(columns::COUNT);
    names.extend(columns::STD);
    names.push(columns::TEMP);
    names.extend(columns::GYRO);
    names.push(label_column);
    names
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
