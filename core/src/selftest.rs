//! A self-test's result as a person reads it: the sensor, the trim codes and outputs it measured,
//! each axis's verdict; its report (text and JSON) and an earlier self-test kept beside a session.
//! Running the self-test on a board is the host's (`accelcal::selftest`).

pub mod report;

use serde::{Deserialize, Serialize};
use shared::protocol::SensorIdentity;
use shared::selftest::{self, AxisVerdict, SelfTestRaw};

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
    /// The deviation of axis `axis` (0-5) in percent; `None` when it had no factory trim.
    pub fn deviation_percent(&self, axis: usize) -> Option<f32> {
        self.result["axes"][axis]["deviation_percent"].as_f64().map(|v| v as f32)
    }
}
