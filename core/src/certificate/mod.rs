//! A board's calibration certificate: who, when, how, under which conditions, every parameter with
//! its standard uncertainty `u` and expanded uncertainty `U` (k = 2) from the uncertainty budget, the
//! errors it predicts at fresh orientations, the verification, and a SHA-256 hash of its content so
//! that a changed copy is detected.

pub mod budget;
pub mod estimate;
pub mod html;
mod seal;

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::data::Dataset;
use crate::fit::drift;
use crate::fit::FitError;
use crate::session::{Board, Session, SessionKind, Verification};
pub use budget::{budget, Budget, Component};
pub use estimate::Estimate;
pub use seal::{check_text, digest_of, SealError};

/// The coverage factor of every expanded uncertainty: k = 2, about 95 % for a normal distribution
/// (GUM 6.2; what an ISO/IEC 17025 certificate states).
pub const COVERAGE_FACTOR: f64 = 2.0;
/// The certificate format written.
pub const FORMAT: u32 = 1;

/// One board's calibration certificate.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Certificate {
    /// The certificate format.
    pub format: u32,
    /// The board: serial, firmware, sensor part, sensor configuration, range, date of the first
    /// capture.
    pub board: Board,
    /// When the calibration's last capture ended, UTC.
    pub date_utc: Option<String>,
    /// How the captures were taken.
    pub method: String,
    /// The model fitted (and the drift with it).
    pub model: String,
    /// The temperature during the session and the unit of g.
    pub conditions: Conditions,
    /// The k of every U.
    pub coverage_factor: f64,
    /// Every parameter by name.
    pub parameters: BTreeMap<String, CertifiedValue>,
    /// The errors the calibration's uncertainty predicts at a fresh orientation.
    pub predicted: Predicted,
    /// The check at fresh orientations, when one was made.
    pub verification: Option<Verification>,
    /// The board's self-test result, where it has one.
    pub self_test: Option<serde_json::Value>,
    /// SHA-256 of the certificate's canonical JSON without this field, in hexadecimal.
    pub sha256: String,
}

/// The conditions of the calibration.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Conditions {
    /// The captures' mean die temperature (where the parameters hold), degC; `None` when the
    /// captures carry no temperature (still periods of a board's own stream).
    pub temp_mean_c: Option<f64>,
    /// Lowest and highest die temperature of the captures, degC (`None` likewise).
    pub temp_low_c: Option<f64>,
    pub temp_high_c: Option<f64>,
    /// The g the outputs are in: 1 = the gravity where the board was captured (|a| = 1 at rest).
    pub g: f64,
    /// Captures the calibration was fitted to.
    pub captures: usize,
}

impl Conditions {
    /// The conditions of `captures` (of `count` captures), their temperatures left unstated where
    /// none carries one.
    fn of(captures: &Dataset, count: usize) -> Self {
        let measured = drift::carries_temperature(captures);
        let (low, high) = drift::span_c(captures);
        let stated = |value: f64| Some(value).filter(|_| measured);
        Conditions {
            temp_mean_c: stated(drift::mean_temp_c(captures)),
            temp_low_c: stated(low),
            temp_high_c: stated(high),
            g: 1.0,
            captures: count,
        }
    }
}

/// A value with its uncertainties.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CertifiedValue {
    pub value: f64,
    /// Standard uncertainty.
    pub u: f64,
    /// Expanded uncertainty, k = 2.
    #[serde(rename = "U")]
    pub expanded: f64,
    /// The unit: 1 (dimensionless), g, g/degC, mg or deg.
    pub unit: String,
    /// The standard uncertainty of each component of the budget.
    pub budget: BTreeMap<Component, f64>,
}

/// The errors predicted at a fresh orientation (RMS over the sphere; U = k u).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Predicted {
    /// | |a| - g |, in mg.
    pub norm_error_mg: Interval,
    /// The angle between the corrected and the true specific force, in degrees.
    pub tilt_error_deg: Interval,
}

/// A predicted error's standard and expanded uncertainty.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Interval {
    pub u: f64,
    #[serde(rename = "U")]
    pub expanded: f64,
}

impl Interval {
    fn of(u: f64) -> Self {
        Interval { u, expanded: mutant!("certificate-predicted-k1", COVERAGE_FACTOR * u, u) }
    }
}

impl Certificate {
    /// The certificate of a session's calibration, sealed; its parameters are those `calibrate`
    /// fits (the calibration uploaded).
    pub fn issue(session: &Session) -> Result<Self, FitError> {
        let estimate = Estimate::of(session)?;
        let budget = budget(session, &estimate)?;
        let captures = session.dataset();
        let mut certificate = Certificate {
            format: FORMAT,
            board: Board::of(session),
            date_utc: session.captures.last().map(|c| crate::shown::utc_minutes(c.unix_time_s)),
            method: method(session),
            model: model(&estimate),
            conditions: Conditions::of(&captures, session.captures.len()),
            coverage_factor: COVERAGE_FACTOR,
            parameters: parameters(&estimate, &budget),
            predicted: Predicted {
                norm_error_mg: Interval::of(budget.prediction.norm_error_mg),
                tilt_error_deg: Interval::of(budget.prediction.tilt_error_deg),
            },
            verification: session.verification.clone(),
            self_test: board_self_test(session),
            sha256: String::new(),
        };
        certificate.sha256 = seal::digest(&certificate);
        Ok(certificate)
    }

    /// The session's own verification when it contradicts the predicted | |a| - g |: the error it
    /// found without its noise exceeds U by more than one noise floor (no certificate is issued then).
    // NOTE: the verified figure carries its own noise: the error without it must exceed U by more than
    // one noise floor to contradict it (as `Verification::against` judges a target).
    pub fn contradicting_verification(&self) -> Option<&Verification> {
        let predicted_mg = self.predicted.norm_error_mg.expanded;
        self.verification.as_ref().filter(|v| v.after_rms_without_noise_mg > predicted_mg + v.noise_floor_mg)
    }

    /// The same certificate sealed again after a test changed it.
    #[cfg(any(test, feature = "sim"))]
    pub fn resealed(mut self) -> Self {
        self.sha256 = seal::digest(&self);
        self
    }

    /// The certificate as pretty JSON.
    pub fn to_json(&self) -> String {
        // NOTE: serialising numbers, strings, maps and options cannot fail.
        serde_json::to_string_pretty(self).unwrap_or_default()
    }
}

/// The self-test the board kept in flash when the session began (`date_utc` and `selftest --json`'s
/// `result`), where it had one.
fn board_self_test(session: &Session) -> Option<serde_json::Value> {
    let entry = session.board.as_ref()?.self_test.as_ref()?;
    serde_json::to_value(entry).ok()
}

/// Every parameter with its budget.
fn parameters(estimate: &Estimate, budget: &Budget) -> BTreeMap<String, CertifiedValue> {
    let entries = estimate.names.iter().enumerate().map(|(k, name)| {
        let u = budget.standard[k];
        let value = CertifiedValue {
            value: estimate.values[k],
            u,
            expanded: mutant!("certificate-parameter-k1", COVERAGE_FACTOR * u, u),
            unit: unit(name).to_owned(),
            budget: budget.contributions[k].clone(),
        };
        (name.clone(), value)
    });
    entries.collect()
}

/// A parameter's unit by its name: offsets in g, drift slopes in g/degC, the matrix's dimensionless.
pub fn unit(name: &str) -> &'static str {
    if name.starts_with("o_") {
        "g"
    } else if name.starts_with("c_") {
        "g/degC"
    } else {
        "1"
    }
}

/// How the captures were taken, in words.
fn method(session: &Session) -> String {
    let positions = session.positions();
    let how = match session.kind {
        SessionKind::Adaptive => "each averaged until its mean was known, in drift-cancelling order",
        SessionKind::Quick => "quick set, fixed-length captures",
        SessionKind::Fixed => "fixed-length captures",
        SessionKind::Stream => "still periods of the board's own stream",
    };
    format!("accelcal calibrate: {positions} static positions ({how}), verified at fresh orientations")
}

/// The model, with the drift when the session fitted it.
fn model(estimate: &Estimate) -> String {
    match estimate.slope_index(0) {
        Some(_) => {
            format!("{} with a linear offset drift per degC, a = M (m - o - c (T - T_mean))", estimate.model.name())
        }
        None => format!("{}, a = M (m - o)", estimate.model.name()),
    }
}

#[cfg(test)]
pub(crate) mod tests;
