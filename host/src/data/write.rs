//! Writing a data file that [`Dataset::from_path`] reads back: the reading and the capture
//! statistics, and a last column of labels.

use super::columns;
use super::{Dataset, Row};

impl Dataset {
    /// The rows as CSV with the capture-statistics columns and a last column `label_column` holding
    /// `labels` (quoted where a label holds a comma or a quote).
    pub fn to_csv(&self, label_column: &str, labels: &[&str]) -> String {
        let mut writer = csv::WriterBuilder::new().terminator(csv::Terminator::Any(b'\n')).from_writer(Vec::new());
        // NOTE: a csv writer into memory cannot fail, and every cell written is UTF-8.
        let _ = writer.write_record(header(label_column));
        for (row, label) in self.rows.iter().zip(labels) {
            let mut record = cells(row);
            record.push((*label).to_owned());
            let _ = writer.write_record(&record);
        }
        String::from_utf8(writer.into_inner().unwrap_or_default()).unwrap_or_default()
    }
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
