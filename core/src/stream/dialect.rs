//! Which sketch printed a stream, and where its columns are: found from the lines themselves, by
//! the shape most of them share (record prefix, labels, how many values, the separator), or, when
//! a sample is printed over several lines, the cycle of shapes its lines repeat; the header line
//! before them, and the column names in it or the labels; the units the lines name in words.

use super::columns::{name_columns, Columns};
use super::conventions::Dialect;
use super::line::{fields, Fields, Form, Words};
use super::refusal::why_no_samples;
use super::units::{AccelUnit, GyroUnit, UnitWord};
use super::StreamError;
use crate::limits::{DETECTION_LINES, MAX_RECORD_LINES, ONE_LINE_SHARE, RECORD_REPEATS};

/// The shape of a data line: lines of one stream share it.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Shape {
    prefix: Option<String>,
    labels: Vec<String>,
    values: usize,
    commas: bool,
    form: Form,
    units: Vec<Option<UnitWord>>,
}

impl Shape {
    fn of(fields: &Fields) -> Self {
        Shape {
            prefix: fields.prefix.clone(),
            labels: fields.labels.clone(),
            values: fields.values.len(),
            commas: fields.commas,
            form: fields.form,
            units: fields.units.clone(),
        }
    }

    /// Whether two lines' shapes are one.
    fn same(&self, other: &Shape) -> bool {
        (&self.prefix, &self.labels, self.values) == (&other.prefix, &other.labels, other.values)
    }

    /// Whether a line has this shape (a CSV line may have a space after its commas).
    pub(super) fn fits(&self, fields: &Fields) -> bool {
        self.prefix == fields.prefix && self.labels == fields.labels && self.values == fields.values.len()
    }
}

/// Records that sketches print between their data and that carry no sample.
pub(super) const SIDE_RECORDS: [&str; 3] = ["Uni", "Cal1", "Cal2"];

/// A stream's dialect, the shapes of the lines of one sample and where the quantities are in them.
#[derive(Debug, Clone, PartialEq)]
pub struct Layout {
    /// The dialect.
    pub dialect: Dialect,
    /// The shapes of the lines that make one sample, in order: one for a sample a line.
    pub(super) record: Vec<Shape>,
    /// The columns of time, accelerometer and gyro (in the values of a sample's lines together),
    /// and the names given to them.
    pub columns: Columns,
    /// The header line (1-based), when there is one.
    pub header_line: Option<usize>,
    /// The units the lines name in words after the accelerometer's and the gyro's values.
    pub said: (Option<AccelUnit>, Option<GyroUnit>),
}

impl Layout {
    /// Finds the dialect and its columns from the first [`DETECTION_LINES`] lines.
    pub fn detect<'a>(lines: impl IntoIterator<Item = &'a str>) -> Result<Layout, StreamError> {
        let lines: Vec<&str> = lines.into_iter().take(DETECTION_LINES).collect();
        let parsed: Vec<Result<Fields, Words>> = lines.iter().map(|l| fields(l)).collect();
        let no_data = || StreamError::NoData { lines: lines.len(), why: why_no_samples(&lines) };
        let record = record_of(&parsed).ok_or_else(no_data)?;
        let header = header_before(&parsed, &record[0]).filter(|_| record.len() == 1);
        let labels: Vec<String> = record.iter().flat_map(|shape| shape.labels.clone()).collect();
        let names = header.as_ref().map(|(_, names)| names.clone()).unwrap_or(labels);
        let dialect = dialect_of(&record, &names);
        let data: Vec<&Fields> = parsed.iter().filter_map(|p| p.as_ref().ok()).filter(|f| record[0].fits(f)).collect();
        let count = record.iter().map(|shape| shape.values).sum();
        let columns = name_columns(dialect, &names, count, &data)?;
        let said = said_units(&record, &columns);
        Ok(Layout { dialect, record, columns, header_line: header.map(|(line, _)| line), said })
    }
}

/// The shapes of one sample's lines: the commonest shape when most data lines have it, else the
/// cycle of shapes the lines repeat (a sample over several lines), else the commonest.
fn record_of(parsed: &[Result<Fields, Words>]) -> Option<Vec<Shape>> {
    let data: Vec<&Fields> = parsed
        .iter()
        .filter_map(|p| p.as_ref().ok())
        .filter(|f| !f.prefix.as_deref().is_some_and(|p| SIDE_RECORDS.contains(&p)))
        .collect();
    let single = commonest_shape(parsed);
    match single {
        Some((shape, count)) if count as f64 >= ONE_LINE_SHARE * data.len() as f64 => Some(vec![shape]),
        _ => cycle(&data).or(single.map(|(shape, _)| vec![shape])),
    }
}

/// The shortest cycle of distinct shapes the data lines repeat, holding three values or more.
fn cycle(data: &[&Fields]) -> Option<Vec<Shape>> {
    (2..=MAX_RECORD_LINES).find_map(|period| {
        let repeats = |i: usize| Shape::of(data[i]).fits(data[i + period]);
        let start = (0..data.len().checked_sub(RECORD_REPEATS * period)?).find(|&i| (i..i + period).all(repeats))?;
        let shapes: Vec<Shape> = data[start..start + period].iter().map(|f| Shape::of(f)).collect();
        let distinct = shapes.iter().enumerate().all(|(i, a)| shapes[..i].iter().all(|b| !a.same(b)));
        let kept = (start..data.len() - period).filter(|&i| repeats(i)).count();
        let most = kept as f64 >= ONE_LINE_SHARE * (data.len() - period - start) as f64;
        (distinct && most && shapes.iter().map(|s| s.values).sum::<usize>() >= 3).then_some(shapes)
    })
}

/// The units the record's lines name after the accelerometer's first value and the gyro's.
fn said_units(record: &[Shape], columns: &Columns) -> (Option<AccelUnit>, Option<GyroUnit>) {
    let units: Vec<Option<UnitWord>> = record.iter().flat_map(|shape| shape.units.clone()).collect();
    let accel = match units.get(columns.accel[0]) {
        Some(Some(UnitWord::Accel(unit))) => Some(*unit),
        _ => None,
    };
    let gyro = match columns.gyro.and_then(|gyro| units.get(gyro[0]).copied().flatten()) {
        Some(UnitWord::Gyro(unit)) => Some(unit),
        _ => None,
    };
    (accel, gyro)
}

/// The shape most data lines have, with how many have it.
fn commonest_shape(parsed: &[Result<Fields, Words>]) -> Option<(Shape, usize)> {
    let mut shapes: Vec<(Shape, usize)> = Vec::new();
    let data = parsed.iter().filter_map(|p| p.as_ref().ok());
    for fields in data.filter(|f| !f.prefix.as_deref().is_some_and(|p| SIDE_RECORDS.contains(&p))) {
        match shapes.iter_mut().find(|(shape, _)| shape.fits(fields)) {
            Some((_, count)) => *count += 1,
            None => shapes.push((Shape::of(fields), 1)),
        }
    }
    shapes.into_iter().filter(|(shape, _)| shape.values >= 3).max_by_key(|(_, count)| *count)
}

/// The header: the last line of names before the first data line, with one name per value.
fn header_before(parsed: &[Result<Fields, Words>], shape: &Shape) -> Option<(usize, Vec<String>)> {
    let first = parsed.iter().position(|p| p.as_ref().is_ok_and(|f| shape.fits(f)))?;
    parsed[..first].iter().enumerate().rev().find_map(|(index, p)| match p {
        Err(Words::Header(names)) if names.len() == shape.values => Some((index + 1, names.clone())),
        _ => None,
    })
}

fn dialect_of(record: &[Shape], names: &[String]) -> Dialect {
    let named = |word: &str| names.iter().any(|n| n.to_ascii_lowercase().contains(word));
    let shape = &record[0];
    match shape.prefix.as_deref() {
        Some("a/g") => Dialect::I2cdevlib,
        Some("Raw") => Dialect::Motioncal,
        Some("()") => Dialect::Micropython,
        _ if record.len() > 1 => Dialect::MultiLine,
        _ if shape.form == Form::DecimalCommas => Dialect::SemicolonCsv,
        _ if shape.form == Form::Braced => Dialect::Json,
        _ if shape.form == Form::Bracketed => Dialect::Array,
        _ if shape.form == Form::Labelled => Dialect::Labelled,
        _ if !shape.labels.is_empty() && named("accelx") => Dialect::AdafruitPlotter,
        _ if !shape.labels.is_empty() => Dialect::SerialPlotter,
        _ if named("omega") && named("alpha") => Dialect::Kalibr,
        _ if shape.commas => Dialect::Csv,
        _ => Dialect::Whitespace,
    }
}
