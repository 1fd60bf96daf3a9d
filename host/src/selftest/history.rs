//! Earlier self-tests of each board, kept on the host in one JSON file per board serial number, so
//! that a run shows the previous result beside the new one (a part that drifts after a drop).
//!
//! The board keeps its latest self-test in flash too ([`shared::selftest::StoredSelfTest`]), so a run
//! on another host still shows the one before; the file keeps every one, and survives a reflash that
//! erases the board's flash.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::files::write_atomically;

/// One earlier self-test.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct HistoryEntry {
    /// When it ran, UTC, to the minute.
    pub date_utc: String,
    /// What `selftest --json` printed (kept as it was, whatever a later accelcal prints).
    pub result: serde_json::Value,
}

impl HistoryEntry {
    /// The deviation of axis `axis` (0-5) in percent; `None` when it had no factory trim.
    pub fn deviation_percent(&self, axis: usize) -> Option<f32> {
        self.result["axes"][axis]["deviation_percent"].as_f64().map(|v| v as f32)
    }
}

/// Why the history could not be read or written.
#[derive(Debug, thiserror::Error)]
pub enum HistoryError {
    #[error("cannot read the self-test history {}: {source}; move it away to start a new one", .path.display())]
    Read { path: PathBuf, source: std::io::Error },
    #[error("the self-test history {} is not one accelcal wrote ({source}); move it away to start a new one", .path.display())]
    Corrupt { path: PathBuf, source: serde_json::Error },
    #[error("cannot keep the self-test in the history {}: {reason}; give another folder with --history", .path.display())]
    Write { path: PathBuf, reason: String },
}

/// The history file of one board.
pub struct History {
    path: PathBuf,
}

impl History {
    /// The history of the board `serial` in `dir`.
    pub fn of(dir: &Path, serial: &str) -> Self {
        History { path: dir.join(format!("selftest-{serial}.json")) }
    }

    /// The file.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Every earlier self-test, oldest first; none when there is no file yet.
    pub fn entries(&self) -> Result<Vec<HistoryEntry>, HistoryError> {
        let text = match std::fs::read_to_string(&self.path) {
            Ok(text) => text,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Vec::new()),
            Err(source) => return Err(HistoryError::Read { path: self.path.clone(), source }),
        };
        serde_json::from_str(&text).map_err(|source| HistoryError::Corrupt { path: self.path.clone(), source })
    }

    /// Adds a self-test to the end, writing the file atomically (the old one stays on a failure).
    pub fn append(&self, entry: HistoryEntry) -> Result<(), HistoryError> {
        let mut entries = self.entries()?;
        entries.push(entry);
        let failed = |reason: String| HistoryError::Write { path: self.path.clone(), reason };
        if let Some(dir) = self.path.parent() {
            std::fs::create_dir_all(dir).map_err(|e| failed(e.to_string()))?;
        }
        let json = serde_json::to_vec_pretty(&entries).map_err(|e| failed(e.to_string()))?;
        write_atomically(&self.path, &json).map_err(|e| failed(e.to_string()))
    }
}

/// Where a real board's self-tests are kept unless `--history` says otherwise:
/// `$XDG_DATA_HOME/accelcal`, else `~/.local/share/accelcal`; `None` without either variable.
pub fn default_dir() -> Option<PathBuf> {
    let data = std::env::var_os("XDG_DATA_HOME").filter(|v| !v.is_empty()).map(PathBuf::from);
    let home = || std::env::var_os("HOME").map(|home| Path::new(&home).join(".local/share"));
    data.or_else(home).map(|dir| dir.join("accelcal"))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn entry(deviation: f32) -> HistoryEntry {
        let result =
            serde_json::json!({ "passed": true, "axes": [{ "axis": "accel_x", "deviation_percent": deviation }] });
        HistoryEntry { date_utc: "2026-11-25 01:00".into(), result }
    }

    #[test]
    fn entries_are_kept_in_order_per_board_and_a_corrupt_file_is_named_not_overwritten() {
        let dir = std::env::temp_dir().join(format!("accelcal-history-{}", std::process::id()));
        let history = History::of(&dir, "0123");
        assert!(history.entries().unwrap().is_empty());
        for deviation in [2.5, 9.0] {
            history.append(entry(deviation)).unwrap();
        }
        let entries = history.entries().unwrap();
        assert_eq!(entries.iter().map(|e| e.deviation_percent(0)).collect::<Vec<_>>(), [Some(2.5), Some(9.0)]);
        assert!(History::of(&dir, "4567").entries().unwrap().is_empty(), "another board's history is its own");
        std::fs::write(history.path(), b"{ not json").unwrap();
        let error = history.append(entry(1.0)).unwrap_err();
        assert!(matches!(error, HistoryError::Corrupt { .. }), "{error}");
        assert_eq!(std::fs::read(history.path()).unwrap(), b"{ not json", "nothing lost");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
