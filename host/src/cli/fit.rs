//! `accelcal fit FILE`: a data file fitted, reported as text or JSON.

use super::args::FitArgs;
use crate::data::Dataset;
use crate::error::Error;
use crate::fit::FitOptions;
use crate::report::{self, FitReport};

/// Reads the file, fits, and prints the report.
pub(super) fn fit(args: &FitArgs) -> Result<(), Error> {
    if !(args.g.is_finite() && args.g > 0.0) {
        return Err(Error::BadGravity { g: args.g });
    }
    let dataset = Dataset::from_path(&args.file, args.g).map_err(|source| Error::data_file(&args.file, source))?;
    let report = FitReport::new(&dataset, args.model, &options(args)).map_err(|source| Error::CannotFit {
        path: args.file.clone(),
        model: args.model,
        source,
    })?;
    if args.json {
        println!("{}", report::json::fit_report(&report));
    } else {
        print!("{}", report::text::fit_report(&report));
    }
    Ok(())
}

fn options(args: &FitArgs) -> FitOptions {
    FitOptions {
        g: args.g,
        face_tolerance_deg: args.face_tolerance_deg,
        training_rows: args.rows.clone().map(|r| r.0),
        reference_rows: args.reference_rows.clone().map(|r| r.0),
    }
}
