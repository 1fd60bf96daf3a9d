//! The board a session was captured on: the record a resumed session is checked against, and what
//! a report or a certificate shows of it.

use std::path::Path;

use serde::{Deserialize, Serialize};
use shared::protocol::{DeviceInfo, FirmwareVersion, SensorConfig};

use super::{Session, SessionError};
use crate::limits::RESUME_RATE_TOLERANCE;
use crate::selftest::HistoryEntry;
use crate::shown::utc_minutes;

/// The board a session was captured on: a resumed session must continue on the same board, at the
/// same range and filter.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BoardRecord {
    /// The board's serial number, 24 hexadecimal digits.
    pub serial: String,
    /// The firmware version that captured.
    pub firmware: FirmwareVersion,
    /// Range, sample rate and filter of the sensor.
    pub config: SensorConfig,
    /// The sensor part as [`crate::part::describe`] names it (absent in sessions before issue 27).
    #[serde(default)]
    pub sensor: Option<String>,
    /// The latest self-test the board kept in flash when the session began (`date_utc`, `result`
    /// as `selftest --json` prints it); absent when it had none, and in sessions before it kept one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub self_test: Option<HistoryEntry>,
}

impl BoardRecord {
    /// The board that answered `info`.
    pub fn of(info: &DeviceInfo) -> Self {
        let serial = String::from_utf8_lossy(&info.serial.hex()).into_owned();
        let sensor = info.sensor.as_ref().ok().map(crate::part::describe);
        let self_test = match (info.sensor, &info.self_test) {
            (Ok(identity), Some(record)) => HistoryEntry::of_board(identity, record),
            _ => None,
        };
        BoardRecord { serial, firmware: info.firmware, config: info.config, sensor, self_test }
    }

    /// Whether a session captured on `self` may continue on `board`; the reason when not.
    pub fn check_same(&self, board: &BoardRecord, path: &Path) -> Result<(), SessionError> {
        let path = path.to_owned();
        if self.serial != board.serial {
            return Err(SessionError::OtherBoard { path, session: self.serial.clone(), board: board.serial.clone() });
        }
        let setting = |c: &SensorConfig| {
            let (range, filter) = (c.range.full_scale_g(), c.filter.bandwidth_hz());
            format!("+-{range} g with the {filter} Hz filter at {} Hz", c.sample_rate_hz)
        };
        let (rate, other_rate) = (f64::from(self.config.sample_rate_hz), f64::from(board.config.sample_rate_hz));
        // NOTE: a rate the board achieves a little differently (99 for 100 Hz) measures the same; a
        // board left at 1000 Hz by `record` filters and averages otherwise.
        let rate_differs = (rate - other_rate).abs() > RESUME_RATE_TOLERANCE * rate;
        let setting_differs = mutant!(
            "resume-other-filter",
            (self.config.range, self.config.filter) != (board.config.range, board.config.filter),
            self.config.range != board.config.range
        );
        if setting_differs || rate_differs {
            return Err(SessionError::OtherSetting {
                path,
                session: setting(&self.config),
                board: setting(&board.config),
            });
        }
        Ok(())
    }
}

/// What the session records of the board; `None` where it records nothing.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Board {
    /// The board's serial number.
    pub serial: Option<String>,
    /// The firmware version.
    pub firmware: Option<String>,
    /// The sensor part, named (see `accelcal::part::describe`).
    pub part: Option<String>,
    /// The sensor configuration (range, filter, sample rate).
    pub sensor_config: Option<String>,
    /// The accelerometer range of the captures, full scale in g.
    pub range_g: Option<u8>,
    /// When the first capture ended, UTC (YYYY-MM-DD HH:MM).
    pub date_utc: Option<String>,
}

impl Board {
    /// What `session` records of its board, dated by its first capture.
    pub fn of(session: &Session) -> Self {
        let first = session.captures.first();
        let board = session.board.as_ref();
        Board {
            serial: session.serial(),
            firmware: board.map(|b| format!("{}.{}.{}", b.firmware.major, b.firmware.minor, b.firmware.patch)),
            part: board.and_then(|b| b.sensor.clone()),
            sensor_config: board.map(|b| {
                let c = b.config;
                format!(
                    "+-{} g, {} Hz, low-pass {} Hz",
                    c.range.full_scale_g(),
                    c.sample_rate_hz,
                    c.filter.bandwidth_hz()
                )
            }),
            range_g: first.map(|c| c.stats.range.full_scale_g()),
            date_utc: first.map(|c| utc_minutes(c.unix_time_s)),
        }
    }
}

#[cfg(test)]
mod tests {
    use shared::AccelRange;

    use super::*;

    #[test]
    fn a_session_resumes_only_on_its_board_at_its_range_and_filter() {
        use shared::protocol::LowPassFilter;
        let serial = "0123456789abcdef01234567".to_owned();
        let firmware = FirmwareVersion { major: 0, minor: 1, patch: 0 };
        let board = |serial: &str, range, filter| BoardRecord {
            serial: serial.to_owned(),
            firmware,
            config: SensorConfig { range, sample_rate_hz: 100, filter },
            sensor: None,
            self_test: None,
        };
        let recorded = board(&serial, AccelRange::G2, LowPassFilter::Hz44);
        let path = Path::new("session.json");
        // A sample rate the board achieves differently does not change what a capture measures.
        let mut same = recorded.clone();
        same.config.sample_rate_hz = 99;
        assert!(recorded.check_same(&same, path).is_ok());
        let other = |b: BoardRecord| recorded.check_same(&b, path).unwrap_err();
        let error = other(board(&serial, AccelRange::G2, LowPassFilter::Hz21));
        assert!(matches!(error, SessionError::OtherSetting { .. }), "another filter: {error}");
        assert!(
            error
                .to_string()
                .contains("+-2 g with the 44 Hz filter at 100 Hz, the board is set to +-2 g with the 21 Hz"),
            "{error}"
        );
        let error = other(board(&serial, AccelRange::G4, LowPassFilter::Hz44));
        assert!(matches!(error, SessionError::OtherSetting { .. }), "another range: {error}");
        let error = other(board("ffffffffffffffffffffffff", AccelRange::G2, LowPassFilter::Hz44));
        assert!(matches!(error, SessionError::OtherBoard { .. }), "another board: {error}");
        let mut fast = recorded.clone();
        fast.config.sample_rate_hz = 1000;
        let error = other(fast);
        assert!(
            error.to_string().contains("at 100 Hz, the board is set to +-2 g with the 44 Hz filter at 1000 Hz"),
            "{error}"
        );
    }

    #[test]
    fn a_stream_session_s_board_is_keyed_by_the_serial_the_person_gave() {
        let stream = |serial| Some(crate::session::StreamSource::for_tests(None, serial));
        let session = |serial| Session { stream: stream(serial), ..Session::default() };
        assert_eq!(Board::of(&session(Some("desk-3"))).serial.as_deref(), Some("desk-3"));
        assert_eq!(Board::of(&session(None)).serial, None);
    }
}
