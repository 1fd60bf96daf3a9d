//! A calibration session: every capture with its statistics, wanted orientation, detected face,
//! temperature and time, kept as JSON and as the calibration data CSV of DESIGN.md (their text; the host writes the files,
//! atomically: `accelcal::session`).

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use shared::protocol::CaptureStats;
use shared::{Calibration, Position};

use crate::data::{Dataset, Row};
use crate::fit::gyro::TurnSummary;
use crate::orientation::Orientation;

mod board;
mod error;
#[cfg(any(test, feature = "sim"))]
mod fixture;
mod kind;
mod other;
mod outcome;
mod source;
mod unmeasured;
mod verdict;
mod verification;

pub use board::{Board, BoardRecord};
pub use error::SessionError;
pub use kind::SessionKind;
pub use other::{not_a_session, other_file};
pub use outcome::{Fitted, Outcome, OutcomeError};
pub use source::StreamSource;
pub use verdict::TargetVerdict;
pub use verification::{Check, TurnCheck, Verification, CHIP_SAMPLES};

/// One capture of a session.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CaptureRecord {
    /// What the capture was called ("+X", "+X+Y+Z", or the name given to `accelcal capture`).
    pub name: String,
    /// The orientation the user was asked for, when there was one.
    pub target: Option<Orientation>,
    /// The face the device detected, if the board was at one.
    pub face: Option<Position>,
    /// When the capture ended: seconds since the Unix epoch (UTC).
    pub unix_time_s: f64,
    /// The device's statistics of the capture.
    pub stats: CaptureStats,
    /// Whether this is an adaptive session's closing capture: its first position again, which
    /// measures the drift and is no position of its own (written only when true).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub closing: bool,
}

impl CaptureRecord {
    /// A capture that ended at `unix_time_s` (seconds since 1970, UTC).
    pub fn at(
        name: &str,
        target: Option<Orientation>,
        face: Option<Position>,
        stats: CaptureStats,
        unix_time_s: f64,
    ) -> Self {
        CaptureRecord { name: name.to_owned(), target, face, unix_time_s, stats, closing: false }
    }

    /// The capture as a data row in g.
    fn row(&self, line: usize) -> Row {
        let s = &self.stats;
        Row {
            line,
            reading: s.mean_g.map(f64::from),
            reference: None,
            count: Some(s.samples),
            std: Some(s.std_g.map(f64::from)),
            temp_c: Some(f64::from(s.temp_c)),
            gyro_mean_dps: Some(s.gyro_mean_dps.map(f64::from)),
        }
    }
}

/// Every capture of a calibration, in order.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Session {
    /// The board the captures were taken on (absent in sessions of `accelcal capture`).
    #[serde(default)]
    pub board: Option<BoardRecord>,
    /// How the positions were captured: its calibration and its report are fitted accordingly.
    #[serde(flatten, with = "kind::stored")]
    pub kind: SessionKind,
    /// The captures used for fitting.
    pub captures: Vec<CaptureRecord>,
    /// The check of the calibration at fresh orientations, when one was made.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub verification: Option<Verification>,
    /// The calibration record uploaded to the board (the chip's f32 values, the gyro's G included),
    /// once `calibrate` uploaded it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub uploaded: Option<Calibration>,
    /// The board's calibration when the session began, kept for its learned temperature model
    /// (`accelcal thermal`): an adaptive session's captures are corrected by it and the model goes
    /// on with the new calibration (absent when the board had none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub learned: Option<Calibration>,
    /// The gyro's turns between the positions, when `calibrate` recorded them.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gyro_turns: Option<Vec<TurnSummary>>,
    /// Where a stream session's lines came from (`kind` `stream`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stream: Option<StreamSource>,
}

impl Session {
    /// The board's serial: the one its firmware reported, or the label a stream session was given
    /// (`--serial`).
    pub fn serial(&self) -> Option<String> {
        self.board.as_ref().map(|b| b.serial.clone()).or_else(|| self.stream.as_ref()?.serial.clone())
    }

    /// Whether a JSON object is a session file: its captures as a list, and no calibration of its
    /// own (as `calibrate --json` has).
    pub fn is_session_json(value: &serde_json::Value) -> bool {
        value.get("captures").is_some_and(serde_json::Value::is_array) && value.get("calibration").is_none()
    }

    /// A session file's JSON, as [`Session::load`] reads it (`temp_c` null in a stream session).
    pub fn from_json(json: serde_json::Value) -> Result<Self, serde_json::Error> {
        unmeasured::from_value(json)
    }

    /// Whether a capture of this name was taken.
    pub fn has_capture(&self, name: &str) -> bool {
        self.captures.iter().any(|c| c.name == name)
    }

    /// The positions the captures were taken at: every capture but the closing one.
    pub fn positions(&self) -> usize {
        self.captures.iter().filter(|c| !c.closing).count()
    }

    /// The captures as a data set in g, with their capture statistics (a stream's without a
    /// temperature: it carries none).
    pub fn dataset(&self) -> Dataset {
        let mut rows: Vec<Row> = self.captures.iter().enumerate().map(|(i, c)| c.row(i + 2)).collect();
        if self.kind == SessionKind::Stream {
            rows.iter_mut().for_each(|row| row.temp_c = None);
        }
        Dataset { rows }
    }

    /// The session as the calibration data CSV (readable by `accelcal fit`).
    pub fn csv(&self) -> String {
        let names: Vec<&str> = self.captures.iter().map(|c| c.name.as_str()).collect();
        self.dataset().to_csv("target", &names)
    }

    /// The session's JSON file as it is kept (a stream session's unmeasured temperatures as null).
    pub fn json_text(&self) -> String {
        // NOTE: serialising plain numbers, strings and options cannot fail.
        match self.kind {
            SessionKind::Stream => unmeasured::stream_json(self),
            _ => serde_json::to_string_pretty(self).unwrap_or_default(),
        }
    }

    /// A session from the text of its JSON file, as [`Session::json_text`] writes it (and as
    /// earlier versions wrote it).
    pub fn from_json_text(text: &str) -> Result<Self, serde_json::Error> {
        unmeasured::parse(text).map(Session::with_closing_marked)
    }

    /// The session with its closing capture marked as such when it was written before captures
    /// carried the mark: an adaptive session's capture named after its first position and " again"
    /// (no other adaptive capture is named so).
    fn with_closing_marked(mut self) -> Self {
        if self.kind == SessionKind::Adaptive && !self.captures.iter().any(|c| c.closing) {
            self.captures.iter_mut().filter(|c| c.name.ends_with(" again")).for_each(|c| c.closing = true);
        }
        self
    }
}

/// A file of the session kept at `stem`: the stem with `.extension` added, so that a name's own
/// dots are kept (`board.1` is kept as `board.1.json`, not `board.json`).
pub fn stem_file(stem: &Path, extension: &str) -> PathBuf {
    let mut name = stem.as_os_str().to_owned();
    name.push(".");
    name.push(extension);
    PathBuf::from(name)
}

/// The stem of a session given by its JSON file (`board.1.json`) or by its stem (`board.1`).
pub fn stem_of(path: &Path) -> PathBuf {
    match path.extension() {
        Some(extension) if extension == "json" => path.with_extension(""),
        _ => path.to_owned(),
    }
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

    fn record(face: Position, z: f32, unix_time_s: f64) -> CaptureRecord {
        let target = Some(Orientation::face(face));
        CaptureRecord {
            name: face.name().into(),
            target,
            face: Some(face),
            unix_time_s,
            stats: stats(z),
            closing: false,
        }
    }

    #[test]
    fn a_session_s_json_reads_back_and_its_csv_reads_as_data() {
        let session = Session {
            board: None,
            kind: SessionKind::Adaptive,
            captures: vec![record(Position::PosZ, 1.0, 1.5), record(Position::NegZ, -1.0, 20.0)],
            ..Session::default()
        };
        assert_eq!(Session::from_json_text(&session.json_text()).unwrap(), session);
        let data = Dataset::from_reader(session.csv().as_bytes(), 1.0).unwrap();
        assert_eq!(data.rows.len(), 2);
        assert_eq!(data.rows[1].reading, [0.01f32 as f64, -0.02f32 as f64, -1.0]);
        assert_eq!(data.rows[0].count, Some(1000));
        assert_eq!(data.rows[0].std, Some([0.003f32 as f64; 3]));
        assert_eq!(data.rows[0].gyro_mean_dps, Some([0.5, -0.25, 0.125]));
        assert_eq!(data, session.dataset());
    }

    #[test]
    fn the_closing_capture_is_marked_and_old_adaptive_files_mark_it_by_its_name() {
        let mut again = record(Position::PosZ, 1.0, 30.0);
        again.name = "+Z again".into();
        let marked = CaptureRecord { closing: true, ..again.clone() };
        let captures = vec![record(Position::PosZ, 1.0, 1.5), record(Position::NegZ, -1.0, 20.0), marked];
        let session = Session { kind: SessionKind::Adaptive, captures, ..Session::default() };
        assert_eq!(session.positions(), 2);
        let text = session.json_text();
        assert_eq!(Session::from_json_text(&text).unwrap(), session);
        // Written before the mark: the adaptive session's "+Z again" is its closing capture.
        let old = text.replace(",\n      \"closing\": true", "");
        assert!(!old.contains("closing"), "{old}");
        assert_eq!(Session::from_json_text(&old).unwrap(), session);
        // A capture that a person named so in a session of fixed captures is a position of its own.
        assert_eq!(Session::from_json_text(&old.replace("\"adaptive\"", "\"fixed\"")).unwrap().positions(), 3);
    }

    #[test]
    fn a_session_name_keeps_its_dots_and_its_json_file_gives_the_same_stem() {
        let (one, two) = (Path::new("out/board.1"), Path::new("out/board.2"));
        assert_eq!(stem_file(one, "json"), Path::new("out/board.1.json"));
        assert_ne!(stem_file(one, "csv"), stem_file(two, "csv"));
        assert_eq!(stem_of(Path::new("out/board.1.json")), one);
        assert_eq!(stem_of(one), one);
    }
}
