//! Which sketch printed a stream, and where its columns are: found from the lines themselves, by
//! the shape most of them share (record prefix, labels, how many values, the separator), the
//! header line before them, and the column names in it.

use super::columns::{name_columns, Columns};
use super::conventions::Dialect;
use super::line::{fields, Fields, Words};
use super::StreamError;
use crate::limits::DETECTION_LINES;

/// The shape of a data line: lines of one stream share it.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Shape {
    prefix: Option<String>,
    labels: Vec<String>,
    values: usize,
    commas: bool,
}

impl Shape {
    fn of(fields: &Fields) -> Self {
        Shape {
            prefix: fields.prefix.clone(),
            labels: fields.labels.clone(),
            values: fields.values.len(),
            commas: fields.commas,
        }
    }

    /// Whether a line has this shape (a CSV line may have a space after its commas).
    pub(super) fn fits(&self, fields: &Fields) -> bool {
        self.prefix == fields.prefix && self.labels == fields.labels && self.values == fields.values.len()
    }
}

/// Records that sketches print between their data and that carry no sample.
pub(super) const SIDE_RECORDS: [&str; 3] = ["Uni", "Cal1", "Cal2"];

/// A stream's dialect, the shape of its data lines and where the quantities are in them.
#[derive(Debug, Clone, PartialEq)]
pub struct Layout {
    /// The dialect.
    pub dialect: Dialect,
    pub(super) shape: Shape,
    /// The columns of time, accelerometer and gyro, and the names given to them.
    pub columns: Columns,
    /// The header line (1-based), when there is one.
    pub header_line: Option<usize>,
}

impl Layout {
    /// Finds the dialect and its columns from the first [`DETECTION_LINES`] lines.
    pub fn detect<'a>(lines: impl IntoIterator<Item = &'a str>) -> Result<Layout, StreamError> {
        let lines: Vec<&str> = lines.into_iter().take(DETECTION_LINES).collect();
        let parsed: Vec<Result<Fields, Words>> = lines.iter().map(|l| fields(l)).collect();
        let shape = commonest_shape(&parsed).ok_or(StreamError::NoData { lines: lines.len() })?;
        let header = header_before(&parsed, &shape);
        let names = header.as_ref().map(|(_, names)| names.clone()).unwrap_or_else(|| shape.labels.clone());
        let dialect = dialect_of(&shape, &names);
        let data: Vec<&Fields> = parsed.iter().filter_map(|p| p.as_ref().ok()).filter(|f| shape.fits(f)).collect();
        let columns = name_columns(dialect, &names, shape.values, &data)?;
        Ok(Layout { dialect, shape, columns, header_line: header.map(|(line, _)| line) })
    }
}

fn commonest_shape(parsed: &[Result<Fields, Words>]) -> Option<Shape> {
    let mut shapes: Vec<(Shape, usize)> = Vec::new();
    let data = parsed.iter().filter_map(|p| p.as_ref().ok());
    for fields in data.filter(|f| !f.prefix.as_deref().is_some_and(|p| SIDE_RECORDS.contains(&p))) {
        match shapes.iter_mut().find(|(shape, _)| shape.fits(fields)) {
            Some((_, count)) => *count += 1,
            None => shapes.push((Shape::of(fields), 1)),
        }
    }
    shapes.into_iter().filter(|(shape, _)| shape.values >= 3).max_by_key(|(_, count)| *count).map(|(shape, _)| shape)
}

/// The header: the last line of names before the first data line, with one name per value.
fn header_before(parsed: &[Result<Fields, Words>], shape: &Shape) -> Option<(usize, Vec<String>)> {
    let first = parsed.iter().position(|p| p.as_ref().is_ok_and(|f| shape.fits(f)))?;
    parsed[..first].iter().enumerate().rev().find_map(|(index, p)| match p {
        Err(Words::Header(names)) if names.len() == shape.values => Some((index + 1, names.clone())),
        _ => None,
    })
}

fn dialect_of(shape: &Shape, names: &[String]) -> Dialect {
    let named = |word: &str| names.iter().any(|n| n.to_ascii_lowercase().contains(word));
    match shape.prefix.as_deref() {
        Some("a/g") => Dialect::I2cdevlib,
        Some("Raw") => Dialect::Motioncal,
        Some("()") => Dialect::Micropython,
        _ if !shape.labels.is_empty() && named("accelx") => Dialect::AdafruitPlotter,
        _ if !shape.labels.is_empty() => Dialect::SerialPlotter,
        _ if named("omega") && named("alpha") => Dialect::Kalibr,
        _ if shape.commas => Dialect::Csv,
        _ => Dialect::Whitespace,
    }
}
