//! What an export starts from: a calibration record (from any JSON accelcal writes, or the board), the
//! board it belongs to when that is known, and the noise terms for Kalibr.

use shared::linalg::{self, Vec3};
use shared::protocol::SensorConfig;
use shared::{AccelRange, Calibration};

use super::loss::Carried;
use shared::protocol::GYRO_RANGE;

use super::ExportError;
use crate::calibration::{self, CalibrationJson};
use crate::fit::drift;
use crate::noise;
use crate::session::{OutcomeError, Session, SessionKind};
use crate::stream::units::{AccelUnit, GyroUnit};

/// A calibration to export and where it came from.
#[derive(Debug, Clone)]
pub struct Source {
    /// The calibration record, as the chip holds it (f32).
    pub calibration: Calibration,
    /// The board's serial number, when what was read records it.
    pub serial: Option<String>,
    /// Where the calibration was read from (a file's path, or the board's port).
    pub from: String,
    /// Kalibr's noise terms, when a noise report was given.
    pub noise: Option<Noise>,
    /// What the readings are that the calibration applies to.
    pub readings: Readings,
}

/// The readings a calibration applies to: the sensor, the gyro's counts and the temperature it was
/// made at, as far as what it was read from records them.
#[derive(Debug, Clone, PartialEq)]
pub struct Readings {
    /// The sensor part as the board named it, when recorded.
    pub sensor: Option<String>,
    /// Gyro values per deg/s of the readings the exported functions take (raw counts, or a
    /// stream's own unit).
    pub gyro_per_dps: f64,
    /// The die temperature the calibration was made at, degC; none where none was measured (a
    /// board's own stream carries none).
    pub made_at_c: Option<f32>,
    /// What a board's own stream printed, when the calibration came from one: the exported code
    /// takes its values as the sketch printed them.
    pub printed: Option<Printed>,
    /// The die temperatures the temperature model was learned over, degC, when what it was read
    /// from records them (a session's own drift: its captures' span).
    pub drift_span_c: Option<(f64, f64)>,
}

/// The units and dialect of a board's own stream.
#[derive(Debug, Clone, PartialEq)]
pub struct Printed {
    /// The accelerometer's unit.
    pub accel: AccelUnit,
    /// The gyro's unit, when recorded.
    pub gyro: Option<GyroUnit>,
    /// The dialect, as `fit LOG --json` names it (`i2cdevlib`, `csv`, ...), when recorded.
    pub dialect: Option<String>,
}

impl Printed {
    /// `accelerometer counts-2g, gyro counts-250dps`.
    pub fn units(&self) -> String {
        let gyro = self.gyro.map_or("not recorded", GyroUnit::name);
        format!("accelerometer {}, gyro {gyro}", self.accel.name())
    }

    /// Whether every value it prints is a whole count (an int16 holds it).
    pub fn counts(&self) -> bool {
        self.accel.is_counts() && self.gyro.is_none_or(GyroUnit::is_counts)
    }
}

impl Readings {
    /// Our firmware's readings: its gyro at +-1000 deg/s.
    pub fn board(sensor: Option<String>, made_at_c: f32) -> Self {
        Readings {
            sensor,
            gyro_per_dps: GYRO_RANGE.lsb_per_dps(),
            made_at_c: Some(made_at_c),
            printed: None,
            drift_span_c: None,
        }
    }

    /// A board's own stream's, its units by the names `fit --json` and a session give them: the
    /// functions take the gyro in the unit it printed (at +-1000 deg/s counts where none is recorded,
    /// as the statement says).
    pub fn stream(accel: AccelUnit, gyro_unit: Option<&str>, dialect: Option<&str>) -> Self {
        let gyro = gyro_unit.and_then(|name| name.parse::<GyroUnit>().ok());
        Readings {
            sensor: None,
            gyro_per_dps: gyro.map_or(GYRO_RANGE.lsb_per_dps(), GyroUnit::per_dps),
            made_at_c: None,
            printed: Some(Printed { accel, gyro, dialect: dialect.map(str::to_owned) }),
            drift_span_c: None,
        }
    }
}

/// Kalibr's four continuous-time noise terms and the sample rate, from `accelcal noise --json`.
#[derive(Debug, Clone, PartialEq)]
pub struct Noise {
    /// Accelerometer white noise, m/s^2/sqrt(Hz) (two-sided, Kalibr's convention).
    pub accel_noise_density: f64,
    /// Accelerometer bias random walk, m/s^3/sqrt(Hz).
    pub accel_random_walk: f64,
    /// Gyro white noise, rad/s/sqrt(Hz).
    pub gyro_noise_density: f64,
    /// Gyro bias random walk, rad/s^2/sqrt(Hz).
    pub gyro_random_walk: f64,
    /// The recording's sample rate, Hz.
    pub rate_hz: f64,
    /// Whether the recording resolved each random walk (else the number is the bound it allows).
    pub random_walks_resolved: [bool; 2],
    /// The serial of the board recorded, when the report names it.
    pub serial: Option<String>,
}

impl Source {
    /// Reads what `calibrate --json`, `fit --json` (in g), `download` or a session file holds.
    pub fn from_text(text: &str, from: &str) -> Result<Self, ExportError> {
        let value: serde_json::Value =
            serde_json::from_str(text).map_err(|e| ExportError::NotJson { reason: e.to_string() })?;
        if Session::is_session_json(&value) {
            let session = Session::from_json(value).map_err(|e| ExportError::NotJson { reason: e.to_string() })?;
            return Self::from_session(&session, from);
        }
        if let Some(unit) = value.get("input_unit").and_then(serde_json::Value::as_str) {
            return Self::from_stream_fit(&value, unit, from);
        }
        let record = CalibrationJson::from_text(text)?;
        let calibration = record.to_device(AccelRange::default())?;
        let readings = Readings::board(None, calibration.mean_temp_c);
        Ok(Source { calibration, serial: None, from: from.to_owned(), noise: None, readings })
    }

    /// What `fit LOG --json` wrote for a board's own stream: M and o in the stream's unit, turned
    /// into g; the gyro's G from the turns when they gave one.
    fn from_stream_fit(value: &serde_json::Value, unit_name: &str, from: &str) -> Result<Self, ExportError> {
        let unit = unit_name.parse::<AccelUnit>().map_err(|_| unknown_unit(unit_name))?;
        let mut record: CalibrationJson =
            serde_json::from_value(value.clone()).map_err(|e| ExportError::NotJson { reason: e.to_string() })?;
        let per_g = unit.per_g();
        // NOTE: a = M (m - o) with m in the unit is (M per_g) (m / per_g - o / per_g) in g.
        record.matrix = record.matrix.map(|row| row.map(|v| v * per_g));
        record.offset = record.offset.map(|v| v / per_g);
        record.gyro_matrix = value.pointer("/gyro_fit/matrix").and_then(|m| serde_json::from_value(m.clone()).ok());
        let calibration = record.to_device(unit.range())?;
        let (gyro_unit, dialect) = (value.get("gyro_unit"), value.get("dialect"));
        let readings = Readings::stream(unit, gyro_unit.and_then(|v| v.as_str()), dialect.and_then(|v| v.as_str()));
        Ok(Source { calibration, serial: None, from: from.to_owned(), noise: None, readings })
    }

    /// The calibration a session's captures give, fitted as `calibrate` fitted it; the gyro's G
    /// (fitted to the moves between positions, which a session file does not keep) from the record
    /// uploaded to the board, where the session kept one.
    pub fn from_session(session: &Session, from: &str) -> Result<Self, ExportError> {
        let config = session.board.as_ref().map_or_else(SensorConfig::default, |b| b.config);
        let outcome = match session.outcome(config) {
            Ok(outcome) => outcome,
            Err(OutcomeError::Fit(e)) => return Err(ExportError::Fit(e)),
            Err(OutcomeError::Calibration(e)) => return Err(e.into()),
        };
        let mut calibration = outcome.calibration;
        if let Some(uploaded) = &session.uploaded {
            calibration.gyro.matrix = uploaded.gyro.matrix;
        }
        let mut readings = match (&session.stream, session.kind) {
            (Some(stream), SessionKind::Stream) => Readings::stream(
                stream.input_unit.parse().map_err(|_| unknown_unit(&stream.input_unit))?,
                stream.gyro_unit.as_deref(),
                Some(&stream.dialect),
            ),
            _ => Readings::board(session.board.as_ref().and_then(|b| b.sensor.clone()), calibration.mean_temp_c),
        };
        // NOTE: a learned model (`accelcal thermal`) was learned over a sweep the session does not record.
        if outcome.fitted.drift.is_some() {
            readings.drift_span_c = drift::temp_span_c(&outcome.fitted.captures);
        }
        Ok(Source { calibration, serial: session.serial(), from: from.to_owned(), noise: None, readings })
    }

    /// The full calibration in f64 (the record's f32 values widened), as the loss's reference.
    pub fn full(&self) -> Carried {
        let (matrix, offset_g) = calibration::static_part(&self.calibration);
        let gyro = &self.calibration.gyro;
        Carried {
            matrix,
            offset_g,
            gyro_matrix: gyro.matrix.map(|row| row.map(f64::from)),
            gyro_bias_dps: Some(gyro.bias_dps.map(f64::from)),
        }
    }

    /// Accelerometer values per g of the readings the exported functions take: raw counts of the
    /// calibration's range, or what a stream printed (m/s^2: 9.80665 a g).
    pub fn accel_per_g(&self) -> f64 {
        self.readings.printed.as_ref().map_or(f64::from(self.calibration.range.lsb_per_g()), |p| p.accel.per_g())
    }

    /// Gyro values per deg/s of the readings the exported functions take.
    pub fn gyro_per_dps(&self) -> f64 {
        self.readings.gyro_per_dps
    }

    /// Whether the exported functions take whole counts (int16), not a stream's decimal values.
    pub fn takes_counts(&self) -> bool {
        self.readings.printed.as_ref().is_none_or(Printed::counts)
    }

    /// The gyro bias in deg/s.
    pub fn gyro_bias_dps(&self) -> Vec3<f64> {
        self.calibration.gyro.bias_dps.map(f64::from)
    }

    /// Whether the gyro's G was fitted (is not the identity).
    pub fn has_gyro_matrix(&self) -> bool {
        self.calibration.gyro.matrix != linalg::identity::<f32>()
    }
}

/// An accelerometer unit accelcal does not name.
fn unknown_unit(name: &str) -> ExportError {
    ExportError::NotJson { reason: format!("unknown input_unit {name:?}") }
}

impl Noise {
    /// Kalibr's numbers from `accelcal noise --json` (its `kalibr.continuous_time` and `sample_rate_hz`).
    pub fn from_text(text: &str) -> Result<Self, ExportError> {
        let report = noise::json::read(text).map_err(|reason| ExportError::NoiseFile { reason })?;
        let lacks = |name: &str| ExportError::NoiseFile {
            reason: format!("no {name}: give the output of `accelcal noise RECORDING --json`"),
        };
        let kalibr = report.kalibr.ok_or_else(|| lacks("kalibr"))?;
        let terms = kalibr.continuous_time;
        Ok(Noise {
            accel_noise_density: terms.accelerometer_noise_density,
            accel_random_walk: terms.accelerometer_random_walk,
            gyro_noise_density: terms.gyroscope_noise_density,
            gyro_random_walk: terms.gyroscope_random_walk,
            rate_hz: report.sample_rate_hz.ok_or_else(|| lacks("sample_rate_hz"))?,
            random_walks_resolved: [kalibr.accelerometer_random_walk_resolved, kalibr.gyroscope_random_walk_resolved],
            serial: report.serial,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::session::StreamSource;

    fn stream_session(gyro_unit: Option<&str>) -> Session {
        let stream = StreamSource::for_tests(gyro_unit, None);
        let session = crate::sim::sessions::adaptive(1, 0.0, 0.004);
        Session { kind: SessionKind::Stream, stream: Some(stream), board: None, ..session }
    }

    #[test]
    fn a_stream_session_exports_for_its_gyro_counts_and_claims_no_temperature() {
        let source = Source::from_session(&stream_session(Some("counts-250dps")), "s.json").unwrap();
        // NOTE: 131 LSB per deg/s at +-250 deg/s (MPU-6050 Product Specification 6.1).
        assert_eq!(source.readings.gyro_per_dps, 131.0);
        assert_eq!(source.readings.made_at_c, None);
        let text = String::from_utf8(crate::export::export(&source, crate::export::Target::C).unwrap().bytes).unwrap();
        assert!(text.contains("#define ACCELCAL_GYRO_LSB_PER_DPS 131.0f"), "{text}");
        assert!(text.contains("made at: die temperature not measured"), "{text}");
        assert!(text.contains("its stream printed accelerometer counts-2g, gyro counts-250dps"), "{text}");
        // The session as its file holds it (temp_c null: not measured) exports the same.
        let written = stream_session(Some("counts-250dps")).json_text();
        assert!(written.contains("\"temp_c\": null"), "{written}");
        let read = Source::from_text(&written, "s.json").unwrap();
        assert_eq!((read.readings.gyro_per_dps, read.readings.made_at_c), (131.0, None));
    }

    #[test]
    fn a_session_s_export_carries_the_gyro_g_it_uploaded() {
        let session = crate::sim::sessions::adaptive(1, 0.0, 0.004);
        let refit = Source::from_session(&session, "s.json").unwrap();
        assert!(!refit.has_gyro_matrix(), "a session without its upload has no moves to fit G to");
        let mut uploaded = refit.calibration;
        uploaded.gyro.matrix = [[1.02, 0.001, 0.0], [0.0, 0.98, -0.002], [0.0, 0.0, 1.01]];
        let session = Session { uploaded: Some(uploaded), ..session };
        let source = Source::from_session(&session, "s.json").unwrap();
        assert_eq!(source.calibration.gyro.matrix, uploaded.gyro.matrix);
        assert_eq!(source.calibration.matrix, refit.calibration.matrix, "the accelerometer stays the refit's");
    }

    #[test]
    fn a_stream_printing_its_gyro_in_deg_per_s_exports_functions_that_take_deg_per_s_as_printed() {
        let source = Source::from_session(&stream_session(Some("deg/s")), "s.json").unwrap();
        assert_eq!(source.readings.gyro_per_dps, 1.0, "the stream's own deg/s, not the firmware's 32.8 counts");
        let text = String::from_utf8(crate::export::export(&source, crate::export::Target::C).unwrap().bytes).unwrap();
        assert!(text.contains("#define ACCELCAL_GYRO_PER_DPS 1.0f"), "{text}");
        assert!(text.contains("accelcal_gyro_dps(const float raw[3], float out_dps[3])"), "{text}");
        assert!(!text.contains("#define ACCELCAL_ACCEL_LSB"), "{text}");
        let board = Source::from_session(&crate::sim::sessions::adaptive(1, 0.0, 0.004), "b.json").unwrap();
        assert_eq!(board.readings.made_at_c, Some(board.calibration.mean_temp_c));
    }
}
