//! The learned bins on disk: written after every capture, so that an interrupted or failed learning
//! run (which may have warmed a board for an hour) loses nothing, and a later run on the same board
//! goes on from them.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::ThermalBins;
use crate::fit::thermal::ThermalPoint;
use crate::session::{write_atomically, SessionError};

/// Why a file of kept bins cannot be gone on from.
#[derive(Debug, thiserror::Error)]
pub enum KeptBinsError {
    #[error("cannot read {path}: {source}; give the --bins file of an earlier `accelcal thermal` run")]
    Read { path: PathBuf, source: std::io::Error },
    #[error("{path} holds no learned bins ({reason}); give the --bins file of an earlier `accelcal thermal` run, or another path")]
    NotBins { path: PathBuf, reason: String },
    #[error("{path} was learned on another board (serial {kept}), this one is {board}: connect that board, or give another --bins path")]
    OtherBoard { path: PathBuf, kept: String, board: String },
}

/// The file's content: the board's serial and every bin.
#[derive(Serialize, Deserialize)]
struct KeptFile {
    /// The serial number of the board that learned the bins.
    serial: String,
    /// Lowest and highest temperature seen, in degC.
    range_c: Option<(f64, f64)>,
    bins: Vec<KeptBin>,
}

/// One bin: orientation number, samples averaged, and the average.
#[derive(Serialize, Deserialize)]
struct KeptBin {
    face: usize,
    samples: usize,
    temp_c: f64,
    force_g: [f64; 3],
    accel_g: [f64; 3],
    gyro_dps: [f64; 3],
}

impl ThermalBins {
    /// Writes the bins learned on the board with this serial to `path` (atomically).
    pub fn save(&self, path: &Path, serial: &str) -> Result<(), SessionError> {
        let bins = self.entries().map(|(face, samples, p)| KeptBin {
            face,
            samples,
            temp_c: p.temp_c,
            force_g: p.force_g,
            accel_g: p.accel_g,
            gyro_dps: p.gyro_dps,
        });
        let file = KeptFile { serial: serial.to_owned(), range_c: self.range_c(), bins: bins.collect() };
        // NOTE: serialising numbers and a string cannot fail.
        write_atomically(path, serde_json::to_string(&file).unwrap_or_default().as_bytes())
    }

    /// The bins kept at `path` by a run on the board with this serial.
    pub fn load(path: &Path, serial: &str) -> Result<Self, KeptBinsError> {
        let text = std::fs::read_to_string(path).map_err(|source| KeptBinsError::Read { path: path.into(), source })?;
        let file: KeptFile = serde_json::from_str(&text)
            .map_err(|e| KeptBinsError::NotBins { path: path.into(), reason: e.to_string() })?;
        if file.serial != serial {
            return Err(KeptBinsError::OtherBoard { path: path.into(), kept: file.serial, board: serial.into() });
        }
        let mut bins = ThermalBins::default();
        for b in file.bins {
            let point = ThermalPoint { temp_c: b.temp_c, force_g: b.force_g, accel_g: b.accel_g, gyro_dps: b.gyro_dps };
            bins.add_point(b.face, point, b.samples as u32);
        }
        (bins.low_c, bins.high_c) = file.range_c.unzip();
        Ok(bins)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use shared::protocol::TempBin;

    #[test]
    fn kept_bins_read_back_as_learned_and_only_for_their_board() {
        let mut bins = ThermalBins::default();
        for (face, temp_c) in [(0, 20.4f32), (0, 20.6), (1, 21.5), (0, 33.2)] {
            let (accel_g, gyro_dps) = ([0.01, temp_c / 1000.0, 1.0], [0.5, 0.0, -0.5]);
            let bin = TempBin { degree_c: temp_c as i8, samples: 100, temp_c, accel_g, gyro_dps };
            bins.add_chip_bin(face, [0.0, 0.0, 1.0], &bin);
        }
        let path = std::env::temp_dir().join(format!("accelcal-kept-bins-{}.json", std::process::id()));
        bins.save(&path, "ABC").unwrap();
        assert_eq!(ThermalBins::load(&path, "ABC").unwrap(), bins);
        let other = ThermalBins::load(&path, "DEF").unwrap_err().to_string();
        assert!(other.contains("another board (serial ABC)"), "{other}");
        std::fs::remove_file(&path).unwrap();
    }
}
