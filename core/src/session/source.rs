//! Where a stream session's lines came from: the port, the log that keeps every line, and what the
//! stream was read as. Its captures are the still periods in g; no temperature comes with them.

use std::path::PathBuf;

use serde::{Deserialize, Serialize};

/// A board's own stream, as a session records it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StreamSource {
    /// The port it was read from.
    pub port: String,
    /// The log that keeps every line read (`accelcal fit LOG` gives the same calibration).
    pub log: PathBuf,
    /// The dialect, as `fit LOG --json` names it.
    pub dialect: String,
    /// The unit the stream prints the accelerometer in (`g`, `counts-2g`, ...).
    pub input_unit: String,
    /// The unit it prints the gyro in (`deg/s`, `counts-250dps`, ...), when it prints one (absent in
    /// sessions before it was kept).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gyro_unit: Option<String>,
    /// Samples a second, when known.
    pub rate_hz: Option<f64>,
    /// The board's serial or label as the person gave it (`--serial`), which its certificate and
    /// the lot key it by; absent when none was given.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub serial: Option<String>,
}

#[cfg(any(test, feature = "sim"))]
impl StreamSource {
    /// A CSV stream of counts at 100 Hz read from /dev/ttyUSB0, for tests.
    pub fn for_tests(gyro_unit: Option<&str>, serial: Option<&str>) -> Self {
        StreamSource {
            port: "/dev/ttyUSB0".into(),
            log: "s.log".into(),
            dialect: "csv".into(),
            input_unit: "counts-2g".into(),
            gyro_unit: gyro_unit.map(str::to_owned),
            rate_hz: Some(100.0),
            serial: serial.map(str::to_owned),
        }
    }
}
