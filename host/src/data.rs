//! The calibration data file of DESIGN.md: a CSV with a header row, one averaged reading per row.
//!
//! Columns: `x,y,z` the averaged reading in any unit; optional `ref_x,ref_y,ref_z` the known specific
//! force in output units (cells empty where the orientation is unknown); any other columns are carried
//! along. The published data sets' own headers are accepted too: `mx,my,mz` or `raw_x,raw_y,raw_z` for
//! the reading, and `incl_deg,toolface_deg` (data/README.md) for a known orientation.

use std::io::Read;
use std::path::Path;

use shared::orientation::from_inclination_toolface;

/// Accepted names of the three reading columns, in order of preference.
const READING_COLUMNS: [[&str; 3]; 3] = [["x", "y", "z"], ["mx", "my", "mz"], ["raw_x", "raw_y", "raw_z"]];
/// Names of the known-specific-force columns.
const REFERENCE_COLUMNS: [&str; 3] = ["ref_x", "ref_y", "ref_z"];
/// Names of the inclination and toolface columns of the published lab data, in degrees.
const ANGLE_COLUMNS: [&str; 2] = ["incl_deg", "toolface_deg"];

/// One averaged reading.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// Line number in the file (the header is line 1).
    pub line: usize,
    /// Averaged reading, in the file's unit.
    pub reading: [f64; 3],
    /// Known specific force in output units, when the orientation is known.
    pub reference: Option<[f64; 3]>,
    /// The other columns' cells, in the order of [`Dataset::extra_columns`].
    pub extra: Vec<String>,
}

/// A whole calibration data file.
#[derive(Debug, Clone, PartialEq)]
pub struct Dataset {
    /// The rows, in file order.
    pub rows: Vec<Row>,
    /// Names of the carried-along columns.
    pub extra_columns: Vec<String>,
}

/// A list of 1-based data-row numbers, written like `1-20` or `1,10,12-14`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RowList(pub Vec<usize>);

impl std::str::FromStr for RowList {
    type Err = String;

    fn from_str(text: &str) -> Result<Self, String> {
        parse_row_list(text).map(RowList)
    }
}

/// Parses a list of 1-based row numbers such as `1-20` or `1,10,12-14`.
pub fn parse_row_list(text: &str) -> Result<Vec<usize>, String> {
    let mut rows = Vec::new();
    for part in text.split(',').map(str::trim) {
        let number = |s: &str| s.trim().parse::<usize>().ok().filter(|&n| n > 0);
        let bad = || format!("{part:?} is not a row number or a range like 1-20 (rows count from 1)");
        match part.split_once('-') {
            Some((first, last)) => {
                let (first, last) = (number(first).ok_or_else(bad)?, number(last).ok_or_else(bad)?);
                if first > last {
                    return Err(bad());
                }
                rows.extend(first..=last);
            }
            None => rows.push(number(part).ok_or_else(bad)?),
        }
    }
    Ok(rows)
}

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
    #[error("line {line}, column {column}: the reading is empty")]
    EmptyReading { line: usize, column: String },
    #[error("line {line}: {reason}")]
    BadRow { line: usize, reason: String },
    #[error("the file has a header but no data rows; add one averaged reading per line")]
    NoRows,
}

/// Where the rows' known orientation comes from.
#[derive(Debug, Clone, Copy)]
enum ReferenceColumns {
    None,
    SpecificForce([usize; 3]),
    Angles([usize; 2]),
}

impl Dataset {
    /// Reads a data file; `g` is |gravity| in output units, used for references given as angles.
    pub fn from_path(path: &Path, g: f64) -> Result<Self, DataError> {
        let file =
            std::fs::File::open(path).map_err(|source| DataError::Io { path: path.display().to_string(), source })?;
        Self::from_reader(file, g)
    }

    /// Reads CSV text from any reader; `g` as in [`Dataset::from_path`].
    pub fn from_reader(reader: impl Read, g: f64) -> Result<Self, DataError> {
        let mut csv = csv::ReaderBuilder::new().trim(csv::Trim::All).from_reader(reader);
        let header: Vec<String> = csv.headers().map_err(|e| csv_error(e, 1))?.iter().map(str::to_owned).collect();
        let layout = Layout::from_header(&header)?;
        let mut rows = Vec::new();
        for record in csv.records() {
            let record = record.map_err(|e| csv_error(e, rows.len() + 2))?;
            let line = record.position().map_or(rows.len() + 2, |p| p.line() as usize);
            rows.push(layout.row(&header, &record, line, g)?);
        }
        if rows.is_empty() {
            return Err(DataError::NoRows);
        }
        let extra_columns = layout.extra.iter().map(|&i| header[i].clone()).collect();
        Ok(Dataset { rows, extra_columns })
    }

    /// The rows whose orientation is known.
    pub fn references(&self) -> impl Iterator<Item = (&Row, [f64; 3])> {
        self.rows.iter().filter_map(|row| row.reference.map(|r| (row, r)))
    }

    /// The value of a carried-along column in a row, if the column exists and the cell is a number.
    pub fn extra_value(&self, row: &Row, column: &str) -> Option<f64> {
        let index = self.extra_columns.iter().position(|c| c == column)?;
        row.extra.get(index)?.parse().ok()
    }
}

/// Which column holds what.
struct Layout {
    reading: [usize; 3],
    reference: ReferenceColumns,
    extra: Vec<usize>,
}

impl Layout {
    fn from_header(header: &[String]) -> Result<Self, DataError> {
        let find = |name: &str| header.iter().position(|h| h == name);
        let reading = READING_COLUMNS
            .iter()
            .find_map(|names| all_columns(header, names))
            .map(|c| [c[0], c[1], c[2]])
            .ok_or_else(|| DataError::MissingColumns { found: header.join(",") })?;
        let reference = match (all_of(header, &REFERENCE_COLUMNS)?, all_of(header, &ANGLE_COLUMNS)?) {
            (Some(columns), _) => ReferenceColumns::SpecificForce([columns[0], columns[1], columns[2]]),
            (None, Some(columns)) => ReferenceColumns::Angles([columns[0], columns[1]]),
            (None, None) => ReferenceColumns::None,
        };
        let used: Vec<usize> = READING_COLUMNS
            .iter()
            .flatten()
            .chain(&REFERENCE_COLUMNS)
            .chain(&ANGLE_COLUMNS)
            .filter_map(|name| find(name))
            .collect();
        let extra = (0..header.len()).filter(|i| !used.contains(i)).collect();
        Ok(Layout { reading, reference, extra })
    }

    fn row(&self, header: &[String], record: &csv::StringRecord, line: usize, g: f64) -> Result<Row, DataError> {
        let cell = |i: usize| Cell { line, column: &header[i], text: record.get(i).unwrap_or("") };
        let mut reading = [0.0; 3];
        for (value, &i) in reading.iter_mut().zip(&self.reading) {
            *value = cell(i).number()?.ok_or_else(|| DataError::EmptyReading { line, column: header[i].clone() })?;
        }
        let reference = match self.reference {
            ReferenceColumns::None => None,
            ReferenceColumns::SpecificForce(columns) => {
                all_or_none(line, columns.map(|i| cell(i).number()).into_iter().collect::<Result<_, _>>()?)?
                    .map(|v| [v[0], v[1], v[2]])
            }
            ReferenceColumns::Angles(columns) => {
                all_or_none(line, columns.map(|i| cell(i).number()).into_iter().collect::<Result<_, _>>()?)?
                    .map(|v| from_inclination_toolface(v[0], v[1]).map(|unit| unit * g))
            }
        };
        let extra = self.extra.iter().map(|&i| cell(i).text.to_owned()).collect();
        Ok(Row { line, reading, reference, extra })
    }
}

/// One cell, with what is needed to name it in an error.
struct Cell<'a> {
    line: usize,
    column: &'a str,
    text: &'a str,
}

impl Cell<'_> {
    /// The cell's number; `None` when empty. "nan" and "inf" are refused like any other non-number.
    fn number(&self) -> Result<Option<f64>, DataError> {
        if self.text.is_empty() {
            return Ok(None);
        }
        match self.text.parse::<f64>() {
            Ok(value) if value.is_finite() => Ok(Some(value)),
            _ => Err(DataError::NotANumber {
                line: self.line,
                column: self.column.to_owned(),
                value: self.text.to_owned(),
            }),
        }
    }
}

/// The indices of all of `names`, or `None` when the header has none of them; an error when only some.
fn all_of(header: &[String], names: &[&str]) -> Result<Option<Vec<usize>>, DataError> {
    let found: Vec<&str> = names.iter().copied().filter(|n| header.iter().any(|h| h == n)).collect();
    match found.len() {
        0 => Ok(None),
        n if n == names.len() => Ok(all_columns(header, names)),
        _ => Err(DataError::PartialColumns { found: found.join(","), expected: names.join(",") }),
    }
}

fn all_columns(header: &[String], names: &[&str]) -> Option<Vec<usize>> {
    names.iter().map(|name| header.iter().position(|h| h == name)).collect()
}

/// All cells of a group filled (`Some`), or all empty (`None`); partly filled is an error.
fn all_or_none(line: usize, cells: Vec<Option<f64>>) -> Result<Option<Vec<f64>>, DataError> {
    match cells.iter().filter(|c| c.is_some()).count() {
        0 => Ok(None),
        n if n == cells.len() => Ok(Some(cells.into_iter().flatten().collect())),
        _ => Err(DataError::BadRow {
            line,
            reason: "the known orientation is only partly given; fill all of its cells or leave them all empty".into(),
        }),
    }
}

fn csv_error(error: csv::Error, fallback_line: usize) -> DataError {
    let line = error.position().map_or(fallback_line, |p| p.line() as usize);
    let reason = match error.kind() {
        csv::ErrorKind::UnequalLengths { expected_len, len, .. } => {
            format!("{len} cells where the header has {expected_len}")
        }
        csv::ErrorKind::Utf8 { .. } => "not valid UTF-8 text".to_owned(),
        _ => error.to_string(),
    };
    DataError::BadRow { line, reason }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(text: &str) -> Result<Dataset, DataError> {
        Dataset::from_reader(text.as_bytes(), 9.81)
    }

    #[test]
    fn reads_readings_references_and_carried_columns() {
        let data =
            read("x,y,z,ref_x,ref_y,ref_z,count,temp_c\n0.1,0.2,9.7,0,0,9.81,1000,25.5\n5,5,5,,,,500,26\n").unwrap();
        assert_eq!(data.rows.len(), 2);
        assert_eq!(data.rows[0].reading, [0.1, 0.2, 9.7]);
        assert_eq!(data.rows[0].reference, Some([0.0, 0.0, 9.81]));
        assert_eq!(data.rows[1].reference, None);
        assert_eq!(data.rows[1].line, 3);
        assert_eq!(data.extra_columns, ["count", "temp_c"]);
        assert_eq!(data.extra_value(&data.rows[1], "temp_c"), Some(26.0));
    }

    #[test]
    fn published_angle_columns_become_references_in_output_units() {
        let data = read("incl_deg,toolface_deg,raw_x,raw_y,raw_z\n0,90,1,2,3\n").unwrap();
        let reference = data.rows[0].reference.unwrap();
        assert!((reference[0] - 9.81).abs() < 1e-12 && reference[1].abs() < 1e-12 && reference[2].abs() < 1e-12);
    }

    #[test]
    fn a_header_without_reading_columns_is_refused_naming_what_it_has() {
        let error = read("a,b,c\n1,2,3\n").unwrap_err().to_string();
        assert!(error.contains("line 1") && error.contains("x,y,z") && error.contains("a,b,c"), "{error}");
    }

    #[test]
    fn partial_reference_columns_are_refused() {
        let error = read("x,y,z,ref_x,ref_y\n1,2,3,4,5\n").unwrap_err().to_string();
        assert!(error.contains("ref_x,ref_y") && error.contains("ref_x,ref_y,ref_z"), "{error}");
    }

    #[test]
    fn a_non_numeric_cell_is_refused_with_line_and_column() {
        let error = read("x,y,z\n1,2,3\n1,two,3\n").unwrap_err().to_string();
        assert_eq!(error, "line 3, column y: \"two\" is not a number");
        let error = read("x,y,z\n1,NaN,3\n").unwrap_err().to_string();
        assert_eq!(error, "line 2, column y: \"NaN\" is not a number");
    }

    #[test]
    fn ragged_rows_empty_readings_and_partial_references_are_refused_with_the_line() {
        assert_eq!(read("x,y,z\n1,2,3\n1,2\n").unwrap_err().to_string(), "line 3: 2 cells where the header has 3");
        assert_eq!(read("x,y,z\n1,,3\n").unwrap_err().to_string(), "line 2, column y: the reading is empty");
        let error = read("x,y,z,ref_x,ref_y,ref_z\n1,2,3,0,,1\n").unwrap_err().to_string();
        assert!(error.starts_with("line 2: the known orientation is only partly given"), "{error}");
    }

    #[test]
    fn row_lists_take_numbers_and_ranges() {
        assert_eq!(parse_row_list("1-3,10"), Ok(vec![1, 2, 3, 10]));
        assert!(parse_row_list("0").is_err());
        assert!(parse_row_list("5-2").unwrap_err().contains("\"5-2\""));
        assert!(parse_row_list("x").is_err());
    }

    #[test]
    fn a_file_without_rows_is_refused() {
        assert!(matches!(read("x,y,z\n"), Err(DataError::NoRows)));
        assert!(matches!(read(""), Err(DataError::MissingColumns { .. })));
    }
}
