//! Each board's calibration as a factory's test executive reads a test run (issue 41): one model of
//! the run (this file), its phases in order (capture, fit, upload, verification, self-test), each
//! certified parameter a measurement with its unit and the spec's limits as validators, and its
//! expanded uncertainty (k = 2) beside it as a measurement of its own (`NAME_U`: neither format has a
//! field for an uncertainty); rendered as an OpenHTF JSON test record (`openhtf.rs`) and as OCP Test &
//! Validation line-delimited JSON artifacts (`ocp.rs`). Units by their UN/CEFACT codes (`units.rs`).

pub mod ocp;
pub mod openhtf;
pub mod units;

use crate::certificate::Certificate;
use crate::lot::{Limits, Spec};

/// The MPU-6050's self-test limit: the response's change from its factory trim within +-14 %
/// (MPU-6000/6050 Product Specification, rev. 3.4, tables 6.1 and 6.2).
const SELF_TEST_LIMIT_PERCENT: f64 = 14.0;

/// One board's calibration as a test run.
#[derive(Debug, Clone, PartialEq)]
pub struct RunRecord {
    /// The board's serial.
    pub dut_id: String,
    /// The station that calibrated it.
    pub station_id: String,
    /// When the calibration ended (the certificate's date), ms since 1970 UTC; 0 when it has none.
    pub end_unix_ms: i64,
    /// The certificate's SHA-256 and model, for the record's metadata.
    pub sha256: String,
    pub model: String,
    pub phases: Vec<Phase>,
}

/// One phase (OpenHTF) or test step (OCP); no measurements means skipped.
#[derive(Debug, Clone, PartialEq)]
pub struct Phase {
    pub name: &'static str,
    pub measurements: Vec<Measured>,
}

/// One measurement in its unit (accelcal's unit text; `None` for a text), with its limits.
#[derive(Debug, Clone, PartialEq)]
pub struct Measured {
    pub name: String,
    pub value: Value,
    pub unit: Option<String>,
    pub limits: Option<Limits>,
}

/// A measured value.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    Number(f64),
    Text(String),
}

/// A measurement's, a phase's or a run's outcome.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outcome {
    Pass,
    Fail,
    Skip,
}

impl Measured {
    fn number(name: impl Into<String>, value: f64, unit: &str, limits: Option<Limits>) -> Self {
        Measured { name: name.into(), value: Value::Number(value), unit: Some(unit.to_owned()), limits }
    }

    fn text(name: &str, value: &str) -> Self {
        Measured { name: name.into(), value: Value::Text(value.into()), unit: None, limits: None }
    }

    /// Pass within the limits (or without any), else fail.
    pub fn outcome(&self) -> Outcome {
        match (&self.value, &self.limits) {
            (Value::Number(value), Some(limits)) if !limits.admits(*value) => Outcome::Fail,
            _ => Outcome::Pass,
        }
    }
}

impl Phase {
    /// Skipped without measurements, failed when one fails.
    pub fn outcome(&self) -> Outcome {
        match self.measurements.is_empty() {
            true => Outcome::Skip,
            false if self.measurements.iter().any(|m| m.outcome() == Outcome::Fail) => Outcome::Fail,
            false => Outcome::Pass,
        }
    }
}

impl RunRecord {
    /// The run of the board a certificate certifies, at `station`, against the spec's limits.
    pub fn of(certificate: &Certificate, station: &str, spec: &Spec) -> Self {
        RunRecord {
            dut_id: certificate.board.serial.clone().unwrap_or_default(),
            station_id: station.to_owned(),
            end_unix_ms: certificate.date_utc.as_deref().and_then(unix_ms).unwrap_or(0),
            sha256: certificate.sha256.clone(),
            model: certificate.model.clone(),
            phases: vec![
                capture(certificate),
                fit(certificate, spec),
                Phase { name: "upload", measurements: upload(certificate, station) },
                verification(certificate),
                self_test(certificate),
            ],
        }
    }

    /// Failed when a phase failed, else passed.
    pub fn outcome(&self) -> Outcome {
        match self.phases.iter().any(|p| p.outcome() == Outcome::Fail) {
            true => Outcome::Fail,
            false => Outcome::Pass,
        }
    }
}

fn capture(certificate: &Certificate) -> Phase {
    let c = &certificate.conditions;
    let mut measurements = vec![Measured::number("captures", c.captures as f64, "1", None)];
    let temperatures = [("temp_mean_c", c.temp_mean_c), ("temp_low_c", c.temp_low_c), ("temp_high_c", c.temp_high_c)];
    for (name, value) in temperatures {
        measurements.extend(value.map(|v| Measured::number(name, v, "degC", None)));
    }
    Phase { name: "capture", measurements }
}

/// Each parameter against its limits, then its U; then the predicted errors' U.
fn fit(certificate: &Certificate, spec: &Spec) -> Phase {
    let mut measurements = Vec::new();
    for (name, p) in &certificate.parameters {
        let unit = p.unit.as_str();
        measurements.push(Measured::number(name.as_str(), p.value, unit, spec.limits.get(name).copied()));
        measurements.push(Measured::number(format!("{name}_U"), p.expanded, unit, None));
    }
    let predicted = &certificate.predicted;
    measurements.push(Measured::number("norm_error_mg_U", predicted.norm_error_mg.expanded, "mg", None));
    measurements.push(Measured::number("tilt_error_deg_U", predicted.tilt_error_deg.expanded, "deg", None));
    Phase { name: "fit", measurements }
}

fn upload(certificate: &Certificate, station: &str) -> Vec<Measured> {
    vec![Measured::text("certificate_sha256", &certificate.sha256), Measured::text("station", station)]
}

fn verification(certificate: &Certificate) -> Phase {
    let measurements = certificate.verification.as_ref().map_or_else(Vec::new, |v| {
        vec![
            Measured::number("positions", v.positions as f64, "1", None),
            Measured::number("after_rms_mg", v.after_rms_mg, "mg", None),
            Measured::number("after_max_mg", v.after_max_mg, "mg", None),
            Measured::number("on_chip_difference_mg", v.on_chip_difference_mg, "mg", None),
        ]
    });
    Phase { name: "verification", measurements }
}

/// Each axis' change from its factory trim against the datasheet's limit, where the board kept one.
fn self_test(certificate: &Certificate) -> Phase {
    let limits = Limits { low: Some(-SELF_TEST_LIMIT_PERCENT), high: Some(SELF_TEST_LIMIT_PERCENT) };
    let axes = certificate.self_test.as_ref().and_then(|s| s["result"]["axes"].as_array().cloned()).unwrap_or_default();
    let measurements = axes
        .iter()
        .filter_map(|axis| {
            let name = format!("{}_deviation_percent", axis["axis"].as_str()?);
            Some(Measured::number(name, axis["deviation_percent"].as_f64()?, "%", Some(limits)))
        })
        .collect();
    Phase { name: "self-test", measurements }
}

/// "YYYY-MM-DD HH:MM" (UTC, as certificates state it) in ms since 1970.
fn unix_ms(date: &str) -> Option<i64> {
    let number = |range: std::ops::Range<usize>| date.get(range)?.parse::<i64>().ok();
    let (year, month, day) = (number(0..4)?, number(5..7)?, number(8..10)?);
    let (hour, minute) = (number(11..13)?, number(14..16)?);
    let month = time::Month::try_from(u8::try_from(month).ok()?).ok()?;
    let day = time::Date::from_calendar_date(i32::try_from(year).ok()?, month, u8::try_from(day).ok()?).ok()?;
    let at = day.with_hms(u8::try_from(hour).ok()?, u8::try_from(minute).ok()?, 0).ok()?;
    Some(at.assume_utc().unix_timestamp() * 1000)
}
