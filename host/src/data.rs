//! Calibration data files: what a data file holds and how its text reads is the core's
//! ([`accelcal_core::data`], re-exported here); this module opens the file.

use std::path::Path;

pub use accelcal_core::data::*;

/// Reads a data file; `g` is |gravity| in output units, used for references given as angles.
pub fn read_file(path: &Path, g: f64) -> Result<Dataset, DataError> {
    let file =
        std::fs::File::open(path).map_err(|source| DataError::Io { path: path.display().to_string(), source })?;
    Dataset::from_reader(file, g)
}
