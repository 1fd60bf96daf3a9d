//! Several boards calibrated on one fixture: what became of each board (its report, no upload, or
//! why it failed), rendered as text and as `calibrate --boards/--ports --json`, and the fixture's
//! outcome (the boards that failed, the boards that missed their target).

use std::fmt::Display;

use serde::Serialize;

use super::text::calibrate_report;
use super::CalibrateReport;

/// What became of one board on the fixture.
#[derive(Debug, Clone)]
pub enum BoardEnd {
    /// Calibrated, uploaded and saved: its report.
    Calibrated(Box<CalibrateReport>),
    /// Its session ended without an upload.
    NotUploaded,
    /// Its session failed: why, as the person reads it.
    Failed(String),
}

impl BoardEnd {
    /// What a board's session returned: its report (none when nothing was uploaded), or its error.
    pub fn of(result: Result<Option<CalibrateReport>, impl Display>) -> Self {
        match result {
            Ok(Some(report)) => BoardEnd::Calibrated(Box::new(report)),
            Ok(None) => BoardEnd::NotUploaded,
            Err(error) => BoardEnd::Failed(error.to_string()),
        }
    }
}

/// One board of the fixture: its serial (the port, when it could not be opened) and its end.
#[derive(Debug, Clone)]
pub struct FixtureBoard {
    /// The board's serial number, or the port it could not be opened on.
    pub serial: String,
    /// What became of it.
    pub end: BoardEnd,
}

/// Every board of one fixture, in the fixture's order.
#[derive(Debug, Clone, Default)]
pub struct FixtureReport {
    /// The boards.
    pub boards: Vec<FixtureBoard>,
}

/// One board in `calibrate --boards/--ports --json`: its `serial` (the port, when it could not be
/// opened) and its report, or its `error`.
#[derive(Serialize)]
struct BoardJson<'a> {
    serial: &'a str,
    #[serde(flatten)]
    report: Option<&'a CalibrateReport>,
    #[serde(skip_serializing_if = "Option::is_none")]
    error: Option<&'a str>,
}

/// `calibrate --boards/--ports --json`.
#[derive(Serialize)]
struct FixtureJson<'a> {
    boards: Vec<BoardJson<'a>>,
}

impl FixtureReport {
    /// Each calibrated board's report as text, opened by `board SERIAL:`.
    pub fn text(&self) -> String {
        let calibrated = self.boards.iter().filter_map(|board| match &board.end {
            BoardEnd::Calibrated(report) => Some(format!("board {}:\n{}", board.serial, calibrate_report(report))),
            _ => None,
        });
        calibrated.collect()
    }

    /// `calibrate --boards/--ports --json`: `boards`, each its `serial` and its report (as
    /// `calibrate --json` prints it) or its `error`.
    pub fn json(&self) -> String {
        let boards = self.boards.iter().map(|board| {
            let (report, error) = match &board.end {
                BoardEnd::Calibrated(report) => (Some(report.as_ref()), None),
                BoardEnd::NotUploaded => (None, Some("not uploaded")),
                BoardEnd::Failed(error) => (None, Some(error.as_str())),
            };
            BoardJson { serial: &board.serial, report, error }
        });
        // NOTE: the reports hold only numbers, strings, options and maps with string keys, which always
        // serialise (as report::json says of each).
        serde_json::to_string_pretty(&FixtureJson { boards: boards.collect() }).unwrap_or_default()
    }

    /// `board SERIAL: why` for each board that failed, joined by `; `; none when none failed.
    pub fn failed(&self) -> Option<String> {
        let failed = self.boards.iter().filter_map(|board| match &board.end {
            BoardEnd::Failed(error) => Some(format!("board {}: {error}", board.serial)),
            _ => None,
        });
        joined(failed)
    }

    /// How many boards did not fail (calibrated, or ended without an upload).
    pub fn not_failed(&self) -> usize {
        self.boards.iter().filter(|board| !matches!(board.end, BoardEnd::Failed(_))).count()
    }

    /// `board SERIAL: why` for each board whose calibration missed its target, joined by `; `; none
    /// when none missed.
    pub fn missed(&self) -> Option<String> {
        let missed = self.boards.iter().filter_map(|board| {
            let BoardEnd::Calibrated(report) = &board.end else { return None };
            let target = report.target.as_ref().filter(|t| t.missed)?;
            Some(format!("board {}: {}", board.serial, target.line))
        });
        joined(missed)
    }
}

/// The lines joined by `; `, or none when there are none.
fn joined(lines: impl Iterator<Item = String>) -> Option<String> {
    let lines: Vec<String> = lines.collect();
    (!lines.is_empty()).then(|| lines.join("; "))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::session::{TargetVerdict, Verification};
    use shared::{AccelRange, Calibration};

    /// A calibrated board's report, verified at 0.25 mg, its target missed or not.
    fn calibrated(missed: bool) -> BoardEnd {
        let verification = Verification {
            positions: 3,
            before_rms_mg: 40.0,
            after_rms_mg: 0.25,
            after_max_mg: 0.3,
            after_rms_without_noise_mg: 0.2,
            on_chip_difference_mg: 0.0,
            on_chip_noise_mg: 1.0,
            noise_floor_mg: 0.15,
            before_mg: Vec::new(),
            after_mg: Vec::new(),
        };
        let mut report =
            CalibrateReport::new(&Calibration::identity(AccelRange::G2), None, None, None, verification, 14);
        let line = format!("target {}", if missed { "missed" } else { "reached" });
        report.target = Some(TargetVerdict { target_mg: Some(0.1), reached: !missed, trusted: true, missed, line });
        BoardEnd::Calibrated(Box::new(report))
    }

    fn fixture() -> FixtureReport {
        let board = |serial: &str, end| FixtureBoard { serial: serial.to_owned(), end };
        FixtureReport {
            boards: vec![
                board("AA", calibrated(true)),
                board("BB", BoardEnd::NotUploaded),
                board("/dev/ttyACM2", BoardEnd::of(Err::<Option<CalibrateReport>, _>("cannot open it"))),
                board("CC", calibrated(false)),
            ],
        }
    }

    #[test]
    fn the_json_gives_each_board_its_serial_and_its_report_or_its_error() {
        let json: serde_json::Value = serde_json::from_str(&fixture().json()).unwrap();
        let boards = json["boards"].as_array().unwrap();
        let serials: Vec<&str> = boards.iter().map(|b| b["serial"].as_str().unwrap()).collect();
        assert_eq!(serials, ["AA", "BB", "/dev/ttyACM2", "CC"]);
        assert_eq!(boards[0]["verification"]["after_rms_mg"], 0.25);
        assert!(boards[0].get("error").is_none(), "a calibrated board has no error: {}", boards[0]);
        assert_eq!(boards[1], serde_json::json!({ "serial": "BB", "error": "not uploaded" }));
        assert_eq!(boards[2], serde_json::json!({ "serial": "/dev/ttyACM2", "error": "cannot open it" }));
    }

    #[test]
    fn the_text_shows_only_calibrated_boards_and_the_outcome_names_who_failed_and_who_missed() {
        let report = fixture();
        let text = report.text();
        assert!(text.starts_with("board AA:\nverified at 3 fresh orientations:"), "{text}");
        assert!(text.contains("\nboard CC:\nverified at 3"), "{text}");
        assert!(!text.contains("board BB") && !text.contains("ttyACM2"), "{text}");
        assert_eq!(report.failed().as_deref(), Some("board /dev/ttyACM2: cannot open it"));
        assert_eq!(report.not_failed(), 3);
        assert_eq!(report.missed().as_deref(), Some("board AA: target missed"));
        let all_well = FixtureReport { boards: report.boards[3..].to_vec() };
        assert_eq!((all_well.failed(), all_well.missed()), (None, None));
    }
}
