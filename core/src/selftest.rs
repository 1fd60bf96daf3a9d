//! A self-test's result as a person reads it: the sensor, the trim codes and outputs it measured,
//! each axis's verdict; its report (text and JSON) and an earlier self-test kept beside a session.
//! Running the self-test on a board is the host's (`accelcal::selftest`).

pub mod report;

use serde::{Deserialize, Serialize};
use shared::protocol::SensorIdentity;
use shared::selftest::{self, AxisVerdict, SelfTestRaw, StoredSelfTest};

use crate::shown::utc_minutes;
use report::SelfTestJson;

/// A self-test's outcome: the sensor, what was measured and each axis's verdict.
#[derive(Debug, Clone)]
pub struct SelfTest {
    /// The sensor it ran on.
    pub identity: SensorIdentity,
    /// The trim codes and the mean outputs, in LSB at the self-test ranges.
    pub raw: SelfTestRaw,
    /// Accelerometer x, y, z then gyro x, y, z.
    pub verdicts: [AxisVerdict; 6],
}

impl SelfTest {
    /// Whether every axis passed accelcal's band.
    pub fn passed(&self) -> bool {
        selftest::passed(&self.verdicts)
    }
}

/// One earlier self-test.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct HistoryEntry {
    /// When it ran, UTC, to the minute.
    pub date_utc: String,
    /// What `selftest --json` printed (kept as it was, whatever a later accelcal prints).
    pub result: serde_json::Value,
}

impl HistoryEntry {
    /// The entry of a self-test run at `unix_time_s` (seconds since 1970, UTC).
    pub fn at(result: &SelfTestJson, unix_time_s: f64) -> Self {
        let date_utc = utc_minutes(unix_time_s);
        HistoryEntry { date_utc, result: serde_json::to_value(result).unwrap_or_default() }
    }

    /// The entry of the self-test a board keeps in flash (`record`), run on the sensor `identity`;
    /// `None` when the record is not one.
    pub fn of_board(identity: SensorIdentity, record: &[u8]) -> Option<Self> {
        let stored = StoredSelfTest::from_record(record)?;
        let test = SelfTest { identity, raw: stored.raw, verdicts: selftest::evaluate(&stored.raw) };
        let date_utc = utc_minutes(f64::from(stored.unix_time_s));
        Some(HistoryEntry { date_utc, result: serde_json::to_value(SelfTestJson::of(&test)).unwrap_or_default() })
    }

    /// The deviation of axis `axis` (0-5) in percent; `None` when it had no factory trim.
    pub fn deviation_percent(&self, axis: usize) -> Option<f32> {
        self.result["axes"][axis]["deviation_percent"].as_f64().map(|v| v as f32)
    }
}
