//! Sessions kept as files: `PATH.json` and `PATH.csv`, written atomically after every capture so that
//! Ctrl-C, a pulled cable or a crash leave the captures so far. What a session is and what it yields
//! are the core's ([`accelcal_core::session`], re-exported here); this module adds only the files.

use std::path::Path;

pub use accelcal_core::session::*;

pub use crate::files::unix_time_s;
pub use keeping::{default_name, first_free, hold, holder, new_session_path, KeptSession};

mod keeping;

/// A session's files: what the host adds to the core's [`Session`].
pub trait SessionFiles: Sized {
    /// Writes `PATH.json` and `PATH.csv` for a path without extension.
    fn save(&self, stem: &Path) -> Result<(), SessionError>;
    /// Reads a session written by [`SessionFiles::save`] (the JSON file).
    fn load(path: &Path) -> Result<Self, SessionError>;
    /// The session at `PATH.json` when it exists, else an empty one.
    fn load_or_new(stem: &Path) -> Result<Self, SessionError>;
}

impl SessionFiles for Session {
    fn save(&self, stem: &Path) -> Result<(), SessionError> {
        write_atomically(&stem_file(stem, "json"), self.json_text().as_bytes())?;
        write_atomically(&stem_file(stem, "csv"), self.csv().as_bytes())
    }

    fn load(path: &Path) -> Result<Self, SessionError> {
        let text = std::fs::read_to_string(path).map_err(|source| SessionError::Read { path: path.into(), source })?;
        Session::from_json_text(&text).map_err(|e| not_a_session(path, &text, e.to_string()))
    }

    fn load_or_new(stem: &Path) -> Result<Self, SessionError> {
        let path = stem_file(stem, "json");
        if path.exists() {
            Session::load(&path)
        } else {
            Ok(Session::default())
        }
    }
}

/// A capture that ended now.
pub fn capture_now(
    name: &str,
    target: Option<accelcal_core::orientation::Orientation>,
    face: Option<shared::Position>,
    stats: shared::protocol::CaptureStats,
) -> CaptureRecord {
    CaptureRecord::at(name, target, face, stats, unix_time_s())
}

/// [`crate::files::write_atomically`], its failure a session's error naming the file.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> Result<(), SessionError> {
    crate::files::write_atomically(path, bytes).map_err(|source| SessionError::Write { path: path.into(), source })
}
