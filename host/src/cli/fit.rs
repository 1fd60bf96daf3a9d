//! `accelcal fit FILE`: a data file fitted, reported as text or JSON. A file that is a sketch's raw
//! log (or a data file whose rows are single samples) is read as a stream: its still periods are
//! found, averaged, and fitted.

use super::args::FitArgs;
use crate::data::{DataError, Dataset};
use crate::error::Error;
use crate::fit::FitOptions;
use crate::report::stream::{self, StreamReport};
use crate::report::{self, FitReport};
use crate::stream::{StreamError, StreamLog};

/// Reads the file, fits, and prints the report.
pub(super) fn fit(args: &FitArgs) -> Result<(), Error> {
    if !(args.g.is_finite() && args.g > 0.0) {
        return Err(Error::BadGravity { g: args.g });
    }
    let text =
        crate::stream::read_text(&args.file).map_err(|source| Error::ReadFile { path: args.file.clone(), source })?;
    let text = crate::recording::csv::without_board_column(text);
    match Dataset::from_reader(text.as_bytes(), args.g) {
        Ok(dataset) if !dataset.looks_like_samples() => fit_dataset(args, &dataset),
        Ok(_) => fit_stream(args, &text).map_err(|e| stream_refused(args, e, None)),
        Err(data) => fit_stream(args, &text).map_err(|e| stream_refused(args, e, Some(data))),
    }
}

fn fit_dataset(args: &FitArgs, dataset: &Dataset) -> Result<(), Error> {
    if let Some(size) = dataset.references_in_ms2(args.g) {
        return Err(Error::ReferencesInOtherUnit { path: args.file.clone(), size, g: args.g });
    }
    let spinner = crate::terminal::working(format!("fitting {} rows (--model {})", dataset.rows.len(), args.model));
    let report = FitReport::new(dataset, args.model, &options(args));
    spinner.finish_and_clear();
    let report = report.map_err(|source| Error::CannotFit { path: args.file.clone(), model: args.model, source })?;
    if args.json {
        println!("{}", report::json::fit_report(&report));
    } else {
        print!("{}", report::text::fit_report(&report));
    }
    Ok(())
}

/// Why a file was neither fitted as a data file nor as a stream.
enum StreamRefusal {
    Read(StreamError),
    Fit(crate::report::stream::StreamFitError),
}

fn fit_stream(args: &FitArgs, text: &str) -> Result<(), StreamRefusal> {
    let log = StreamLog::parse(text, &args.stream.options(None)).map_err(StreamRefusal::Read)?;
    let report = StreamReport::new(&log, args.model, &options(args)).map_err(StreamRefusal::Fit)?;
    if args.json {
        println!("{}", stream::json(&report));
    } else {
        print!("{}", stream::text(&report));
    }
    Ok(())
}

/// The error for a file that is not a data file and could not be fitted as a stream: the data
/// file's own error when it has a data file's header (a bad row), else the stream's (which quotes a
/// line and says what it lacks when none holds a sample).
fn stream_refused(args: &FitArgs, refusal: StreamRefusal, data: Option<DataError>) -> Error {
    let headed = |data: &DataError| !matches!(data, DataError::MissingColumns { .. });
    match (refusal, data) {
        (StreamRefusal::Read(_), Some(data)) if headed(&data) => Error::data_file(&args.file, data),
        (StreamRefusal::Read(source), _) => Error::Stream { path: args.file.clone(), source },
        (StreamRefusal::Fit(source), _) => Error::StreamFit { path: args.file.clone(), source },
    }
}

fn options(args: &FitArgs) -> FitOptions {
    FitOptions {
        g: args.g,
        face_tolerance_deg: args.face_tolerance_deg,
        training_rows: args.rows.clone().map(|r| r.0),
        reference_rows: args.reference_rows.clone().map(|r| r.0),
    }
}
