//! A self-test's outcome as `accelcal selftest` prints it: the result beside the board's previous
//! one, with the family its offset registers confirm; as text or as JSON.

use std::path::PathBuf;

use serde::Serialize;

use super::history::HistoryEntry;
use super::report::{text, SelfTestJson};
use super::SelfTest;
use crate::part::check::{FamilyCheck, FamilyCheckJson};

/// What `selftest --json` prints: the result's fields, the board's previous self-test and where
/// they are kept.
#[derive(Serialize)]
struct SelftestOutput<'a> {
    #[serde(flatten)]
    result: &'a SelfTestJson,
    /// The board's previous self-test (`date_utc`, `result`): the newer of the one in its flash and the
    /// history file's last; null for the first.
    previous: Option<&'a HistoryEntry>,
    /// The history file; null when none is kept.
    history: Option<PathBuf>,
    /// What confirmed the family the self-test ran as ("offset registers"), or null (as `info`).
    family_confirmed_by: Option<&'static str>,
    /// The offset-register check of the family (as `info`); null with no sensor.
    family_check: Option<FamilyCheckJson>,
}

/// What a self-test run shows.
pub struct Shown<'a> {
    pub test: &'a SelfTest,
    pub result: &'a SelfTestJson,
    pub previous: Option<&'a HistoryEntry>,
    pub check: Option<&'a FamilyCheck>,
}

impl Shown<'_> {
    /// As JSON (with the history file) or as text, ending in a newline.
    pub fn output(&self, json: bool, history: Option<PathBuf>) -> String {
        if !json {
            let family = self.check.map_or(String::new(), |c| format!("family: {}\n", c.summary()));
            return format!("{}{family}", text(self.test, self.previous));
        }
        let output = SelftestOutput {
            result: self.result,
            previous: self.previous,
            history,
            family_confirmed_by: self.check.and_then(FamilyCheck::confirmed_by),
            family_check: self.check.map(FamilyCheckJson::of),
        };
        format!("{}\n", serde_json::to_string_pretty(&output).unwrap_or_default())
    }
}
