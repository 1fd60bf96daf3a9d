//! A calibration session: every capture with its statistics, position, temperature and time, kept as
//! JSON and as the calibration data CSV of DESIGN.md. Files are written atomically.

use std::fmt::Write as _;
use std::path::Path;

use serde::{Deserialize, Serialize};
use shared::protocol::CaptureStats;

use crate::data::{Dataset, Row};
use crate::error::Error;

/// One capture of a session.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CaptureRecord {
    /// What the user was asked for ("+X", "corner +X+Y+Z", "verification 2", ...).
    pub target: String,
    /// The face the device detected, if the board was at one.
    pub position: Option<String>,
    /// When the capture ended: seconds since the Unix epoch (UTC).
    pub unix_time_s: f64,
    /// The device's statistics of the capture.
    pub stats: CaptureStats,
}

/// Every capture of a calibration, in order.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Session {
    /// The captures used for fitting.
    pub captures: Vec<CaptureRecord>,
}

impl Session {
    /// The captures as a data set in g, with `count`, `std_*`, `temp_c` and the gyro columns.
    pub fn dataset(&self) -> Dataset {
        let extra_columns = ["count", "std_x", "std_y", "std_z", "temp_c", "gyro_x_dps", "gyro_y_dps", "gyro_z_dps"];
        let rows = self
            .captures
            .iter()
            .enumerate()
            .map(|(i, c)| {
                let s = &c.stats;
                let extra = [s.samples as f64]
                    .into_iter()
                    .chain(s.std_g.map(f64::from))
                    .chain([f64::from(s.temp_c)])
                    .chain(s.gyro_mean_dps.map(f64::from))
                    .map(|v| v.to_string())
                    .collect();
                Row { line: i + 2, reading: s.mean_g.map(f64::from), reference: None, extra }
            })
            .collect();
        Dataset { rows, extra_columns: extra_columns.map(String::from).to_vec() }
    }

    /// The session as the calibration data CSV (readable by `accelcal fit`).
    pub fn csv(&self) -> String {
        let dataset = self.dataset();
        let mut out = format!("x,y,z,{},target\n", dataset.extra_columns.join(","));
        for (row, capture) in dataset.rows.iter().zip(&self.captures) {
            let [x, y, z] = row.reading;
            let _ = writeln!(out, "{x},{y},{z},{},{}", row.extra.join(","), capture.target.replace(',', " "));
        }
        out
    }

    /// Writes `PATH.json` and `PATH.csv` for a path without extension.
    pub fn save(&self, stem: &Path) -> Result<(), Error> {
        let json = serde_json::to_string_pretty(self).map_err(|e| Error::Refused(e.to_string()))?;
        write_atomically(&stem.with_extension("json"), json.as_bytes())?;
        write_atomically(&stem.with_extension("csv"), self.csv().as_bytes())
    }

    /// Reads a session written by [`Session::save`] (the JSON file).
    pub fn load(path: &Path) -> Result<Self, Error> {
        let text = std::fs::read_to_string(path).map_err(|e| Error::io(format!("reading {}", path.display()), e))?;
        serde_json::from_str(&text)
            .map_err(|e| Error::Refused(format!("{} is not a session file: {e}", path.display())))
    }
}

/// Now, in seconds since the Unix epoch, for capture records.
pub fn unix_time_s() -> f64 {
    std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0.0, |d| d.as_secs_f64())
}

/// Writes a file so that a crash leaves either the old file or the new one, never half of one:
/// a temporary file beside it, flushed to disk, then renamed over it.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> Result<(), Error> {
    use std::io::Write;
    let temporary = path.with_extension(format!(
        "{}.tmp{}",
        path.extension().and_then(|e| e.to_str()).unwrap_or(""),
        std::process::id()
    ));
    let context = || format!("writing {}", path.display());
    let mut file = std::fs::File::create(&temporary).map_err(|e| Error::io(context(), e))?;
    file.write_all(bytes).and_then(|()| file.sync_all()).map_err(|e| Error::io(context(), e))?;
    std::fs::rename(&temporary, path).map_err(|e| Error::io(context(), e))
}

#[cfg(test)]
mod tests {
    use super::*;
    use shared::AccelRange;

    fn stats(z: f32) -> CaptureStats {
        CaptureStats {
            samples: 1000,
            seconds: 10.0,
            mean_g: [0.01, -0.02, z],
            std_g: [0.003; 3],
            gyro_mean_dps: [0.5, -0.25, 0.125],
            gyro_std_dps: [0.05; 3],
            temp_c: 25.5,
            clipped: 0,
            range: AccelRange::G2,
        }
    }

    #[test]
    fn a_saved_session_reads_back_and_its_csv_reads_as_data() {
        let session = Session {
            captures: vec![
                CaptureRecord { target: "+Z".into(), position: Some("+Z".into()), unix_time_s: 1.5, stats: stats(1.0) },
                CaptureRecord {
                    target: "-Z".into(),
                    position: Some("-Z".into()),
                    unix_time_s: 20.0,
                    stats: stats(-1.0),
                },
            ],
        };
        let stem = std::env::temp_dir().join(format!("accelcal-session-{}", std::process::id()));
        session.save(&stem).unwrap();
        assert_eq!(Session::load(&stem.with_extension("json")).unwrap(), session);
        let data = Dataset::from_path(&stem.with_extension("csv"), 1.0).unwrap();
        assert_eq!(data.rows.len(), 2);
        assert_eq!(data.rows[1].reading, [0.01f32 as f64, -0.02f32 as f64, -1.0]);
        assert_eq!(data.extra_value(&data.rows[0], "count"), Some(1000.0));
        assert_eq!(data.extra_value(&data.rows[0], "std_y"), Some(0.003f32 as f64));
    }
}
