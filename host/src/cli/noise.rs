//! `accelcal noise`: the Allan deviation and noise terms of a still recording, or of the longest
//! still period of a sketch's raw stream.

use super::args::NoiseArgs;
use crate::error::Error;
use crate::noise::input::NoiseInputError;
use crate::noise::{self, input, json, text};

/// `accelcal noise FILE [--json] [--plot FILE.svg]`.
pub(super) fn noise(args: &NoiseArgs) -> Result<(), Error> {
    let reading = crate::terminal::working(format!("reading {}", args.file.display()));
    let series = match input::read_path(&args.file, args.rate) {
        Err(NoiseInputError::MissingColumn { .. } | NoiseInputError::BadLine { .. }) => {
            crate::stream::noise_input::series(&args.file, args.rate)
        }
        read => read.map_err(Error::from),
    };
    reading.finish_and_clear();
    let series = series?;
    let samples = series.axes[0].len();
    let analysing = crate::terminal::working(format!("Allan deviation of {samples} samples per axis"));
    let report = noise::analyse(&series);
    analysing.finish_and_clear();
    if let Some(path) = &args.plot {
        let document = crate::report::allan::svg_document(&json::NoiseJson::of(&report))?;
        std::fs::write(path, document).map_err(|source| Error::WriteFile { path: path.clone(), source })?;
    }
    if args.json {
        println!("{}", json::render(&report));
    } else {
        print!("{}", text::render(&report));
    }
    Ok(())
}
