//! Reading a data file: the header decides which column holds what; every refusal names the line
//! and, for a cell, the column.

use std::io::Read;

use shared::orientation::from_inclination_toolface;

use super::columns;
use super::{DataError, Dataset, Row};

/// Where the rows' known orientation comes from.
#[derive(Debug, Clone, Copy)]
enum ReferenceColumns {
    None,
    SpecificForce([usize; 3]),
    Angles([usize; 2]),
}

/// Which column holds what.
struct Layout {
    reading: [usize; 3],
    reference: ReferenceColumns,
    count: Option<usize>,
    std: Option<[usize; 3]>,
    temp_c: Option<usize>,
    gyro: Option<[usize; 3]>,
}

impl Dataset {
    /// Reads CSV text from any reader; `g` is |gravity| in output units, used for references given
    /// as angles.
    pub fn from_reader(reader: impl Read, g: f64) -> Result<Self, DataError> {
        // NOTE: the csv crate counts a `\r\n` line end as no line at all and so names every line one
        // too low; without the `\r` every line ends at `\n` and is counted as a person counts it.
        let reader = WithoutCarriageReturns(reader);
        let mut csv = csv::ReaderBuilder::new().trim(csv::Trim::All).from_reader(reader);
        let header: Vec<String> = csv.headers().map_err(|e| csv_error(e, 1))?.iter().map(str::to_owned).collect();
        let layout = Layout::from_header(&header)?;
        let mut rows = Vec::new();
        for record in csv.records() {
            let record = record.map_err(|e| csv_error(e, rows.len() + 2))?;
            let line = record.position().map_or(rows.len() + 2, |p| p.line() as usize);
            let cells = Cells { header: &header, record: &record, line };
            rows.push(layout.row(&cells, g)?);
        }
        if rows.is_empty() {
            return Err(DataError::NoRows);
        }
        Ok(Dataset { rows })
    }
}

impl Layout {
    fn from_header(header: &[String]) -> Result<Self, DataError> {
        let reading = columns::READING
            .iter()
            .find_map(|names| all_columns(header, names))
            .ok_or_else(|| DataError::MissingColumns { found: header.join(",") })?;
        let reference = match (all_of(header, &columns::REFERENCE)?, all_of(header, &columns::ANGLES)?) {
            (Some(columns), _) => ReferenceColumns::SpecificForce(columns),
            (None, Some(columns)) => ReferenceColumns::Angles(columns),
            (None, None) => ReferenceColumns::None,
        };
        Ok(Layout {
            reading,
            reference,
            count: column(header, columns::COUNT),
            std: all_of(header, &columns::STD)?,
            temp_c: column(header, columns::TEMP),
            gyro: all_of(header, &columns::GYRO)?,
        })
    }

    fn row(&self, cells: &Cells, g: f64) -> Result<Row, DataError> {
        Ok(Row {
            line: cells.line,
            reading: self.reading(cells)?,
            reference: self.reference(cells, g)?,
            count: self.count.map(|i| cells.count(i)).transpose()?.flatten(),
            std: self.std.map(|c| cells.group(c, "standard deviation")).transpose()?.flatten(),
            temp_c: self.temp_c.map(|i| cells.number(i)).transpose()?.flatten(),
            gyro_mean_dps: self.gyro.map(|c| cells.group(c, "gyro mean")).transpose()?.flatten(),
        })
    }

    fn reading(&self, cells: &Cells) -> Result<[f64; 3], DataError> {
        let mut reading = [0.0; 3];
        for (value, &i) in reading.iter_mut().zip(&self.reading) {
            let empty = || DataError::EmptyReading { line: cells.line, column: cells.header[i].clone() };
            *value = cells.number(i)?.ok_or_else(empty)?;
        }
        Ok(reading)
    }

    fn reference(&self, cells: &Cells, g: f64) -> Result<Option<[f64; 3]>, DataError> {
        const GROUP: &str = "known orientation";
        match self.reference {
            ReferenceColumns::None => Ok(None),
            ReferenceColumns::SpecificForce(columns) => cells.group(columns, GROUP),
            ReferenceColumns::Angles(columns) => Ok(cells
                .group(columns, GROUP)?
                .map(|[incl, toolface]| from_inclination_toolface(incl, toolface).map(|unit| unit * g))),
        }
    }
}

/// The cells of one record, with what is needed to name one in an error.
struct Cells<'a> {
    header: &'a [String],
    record: &'a csv::StringRecord,
    line: usize,
}

impl Cells<'_> {
    fn text(&self, i: usize) -> &str {
        self.record.get(i).unwrap_or("")
    }

    /// The cell's number; `None` when empty. "nan" and "inf" are refused like any other non-number.
    fn number(&self, i: usize) -> Result<Option<f64>, DataError> {
        let text = self.text(i);
        if text.is_empty() {
            return Ok(None);
        }
        match text.parse::<f64>() {
            Ok(value) if value.is_finite() => Ok(Some(value)),
            _ => Err(DataError::NotANumber { line: self.line, column: self.header[i].clone(), value: text.to_owned() }),
        }
    }

    /// The cell's sample count; `None` when empty.
    fn count(&self, i: usize) -> Result<Option<u32>, DataError> {
        let text = self.text(i);
        if text.is_empty() {
            return Ok(None);
        }
        let not_a_count =
            || DataError::NotACount { line: self.line, column: self.header[i].clone(), value: text.to_owned() };
        text.parse::<u32>().map(Some).map_err(|_| not_a_count())
    }

    /// All cells of a group filled (`Some`), or all empty (`None`); partly filled is an error.
    fn group<const N: usize>(&self, columns: [usize; N], group: &'static str) -> Result<Option<[f64; N]>, DataError> {
        let mut values = [0.0; N];
        let mut filled = 0;
        for (value, i) in values.iter_mut().zip(columns) {
            if let Some(number) = self.number(i)? {
                *value = number;
                filled += 1;
            }
        }
        match filled {
            0 => Ok(None),
            n if n == N => Ok(Some(values)),
            _ => Err(DataError::PartlyGiven { line: self.line, group }),
        }
    }
}

/// A reader that drops every `\r`, so that CRLF and LF files read alike.
struct WithoutCarriageReturns<R>(R);

impl<R: Read> Read for WithoutCarriageReturns<R> {
    fn read(&mut self, buffer: &mut [u8]) -> std::io::Result<usize> {
        loop {
            let n = self.0.read(buffer)?;
            let mut kept = 0;
            for i in 0..n {
                buffer[kept] = buffer[i];
                kept += usize::from(buffer[i] != b'\r');
            }
            // A read of nothing but `\r` is not the end of the input: read on.
            if kept > 0 || n == 0 {
                return Ok(kept);
            }
        }
    }
}

fn column(header: &[String], name: &str) -> Option<usize> {
    header.iter().position(|h| h == name)
}

/// The indices of all of `names`, or `None` when the header has none of them; an error when only some.
fn all_of<const N: usize>(header: &[String], names: &[&str; N]) -> Result<Option<[usize; N]>, DataError> {
    let found: Vec<&str> = names.iter().copied().filter(|n| column(header, n).is_some()).collect();
    match found.len() {
        0 => Ok(None),
        n if n == N => Ok(all_columns(header, names)),
        _ => Err(DataError::PartialColumns { found: found.join(","), expected: names.join(",") }),
    }
}

fn all_columns<const N: usize>(header: &[String], names: &[&str; N]) -> Option<[usize; N]> {
    let mut indices = [0; N];
    for (index, name) in indices.iter_mut().zip(names) {
        *index = column(header, name)?;
    }
    Some(indices)
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
    fn reads_readings_references_and_capture_statistics() {
        let data = read(
            "x,y,z,ref_x,ref_y,ref_z,count,std_x,std_y,std_z,temp_c,note\n\
             0.1,0.2,9.7,0,0,9.81,1000,0.01,0.02,0.03,25.5,a\n5,5,5,,,,500,,,,26,b\n",
        )
        .unwrap();
        assert_eq!(data.rows.len(), 2);
        assert_eq!(data.rows[0].reading, [0.1, 0.2, 9.7]);
        assert_eq!(data.rows[0].reference, Some([0.0, 0.0, 9.81]));
        assert_eq!(data.rows[0].std, Some([0.01, 0.02, 0.03]));
        assert_eq!(data.rows[1].reference, None);
        assert_eq!(data.rows[1].line, 3);
        assert_eq!(data.rows[1].count, Some(500));
        assert_eq!(data.rows[1].std, None);
        assert_eq!(data.rows[1].temp_c, Some(26.0));
        assert_eq!(data.rows[1].gyro_mean_dps, None);
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
        let error = read("x,y,z,count\n1,2,3,12.5\n").unwrap_err().to_string();
        assert_eq!(error, "line 2, column count: \"12.5\" is not a sample count");
    }

    #[test]
    fn crlf_line_endings_count_lines_as_a_person_does() {
        let data = read("x,y,z\r\n1,2,3\r\n4,5,6\r\n").unwrap();
        assert_eq!((data.rows[0].line, data.rows[1].line, data.rows[1].reading), (2, 3, [4.0, 5.0, 6.0]));
        let error = read("x,y,z\r\n1,2,3\r\n1,two,3\r\n").unwrap_err().to_string();
        assert_eq!(error, "line 3, column y: \"two\" is not a number");
        assert_eq!(read("x,y,z\r\n1,2\r\n").unwrap_err().to_string(), "line 2: 2 cells where the header has 3");
    }

    #[test]
    fn ragged_rows_empty_readings_and_partial_references_are_refused_with_the_line() {
        assert_eq!(read("x,y,z\n1,2,3\n1,2\n").unwrap_err().to_string(), "line 3: 2 cells where the header has 3");
        assert_eq!(read("x,y,z\n1,,3\n").unwrap_err().to_string(), "line 2, column y: the reading is empty");
        let error = read("x,y,z,ref_x,ref_y,ref_z\n1,2,3,0,,1\n").unwrap_err().to_string();
        assert!(error.starts_with("line 2: the known orientation is only partly given"), "{error}");
    }

    #[test]
    fn a_file_without_rows_is_refused() {
        assert!(matches!(read("x,y,z\n"), Err(DataError::NoRows)));
        assert!(matches!(read(""), Err(DataError::MissingColumns { .. })));
    }
}
