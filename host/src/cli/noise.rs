//! `accelcal noise`: the Allan deviation and noise terms of a still recording.

use super::args::NoiseArgs;
use crate::error::Error;
use crate::noise::{self, input, json, plot, text};

/// `accelcal noise FILE [--json] [--plot FILE.svg]`.
pub(super) fn noise(args: &NoiseArgs) -> Result<(), Error> {
    let series = input::read_path(&args.file, args.rate)?;
    let report = noise::analyse(&series);
    if let Some(path) = &args.plot {
        std::fs::write(path, plot::render(&report))
            .map_err(|source| Error::WriteFile { path: path.clone(), source })?;
    }
    if args.json {
        println!("{}", json::render(&report));
    } else {
        print!("{}", text::render(&report));
    }
    Ok(())
}
