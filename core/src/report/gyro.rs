//! What a calibration reports of the gyro: the G and bias uploaded with their standard errors, why
//! G was not fitted, the moves dropped, the simulated sensor's true gyro correction, and the
//! verification turn.

use serde::Serialize;
use shared::linalg::{identity, Mat3, Vec3};

use super::figure::{Figure, Role, Series, SeriesStyle};
use crate::calibration::CalibrationJson;
use crate::fit::gyro::{GyroFit, TurnSummary};
use crate::session::TurnCheck;

/// `calibration.gyro` of `accelcal calibrate --json`: w = matrix (w_raw - bias_dps).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GyroJson {
    /// G, dimensionless, rows by calibrated axis (the identity when it was not fitted).
    pub matrix: Mat3<f64>,
    /// The bias b at the calibration's mean temperature, deg/s.
    pub bias_dps: Vec3<f64>,
    /// Standard error of every entry of G (absent when G was not fitted).
    pub std_errors: Option<Mat3<f64>>,
    /// Turns the fit used.
    pub turns: usize,
    /// RMS angle, in degrees, between predicted and measured gravity after each turn.
    pub residual_deg: Option<f64>,
    /// Why G was not fitted, with the turns to add.
    pub not_fitted: Option<String>,
    /// Moves between positions not used, each with its cause.
    pub dropped_moves: Vec<String>,
}

/// What the gyro fit of a calibration gave: the fit, or why there is none, and the moves dropped.
#[derive(Debug, Clone, Default)]
pub struct GyroOutcome {
    /// The fit, when it was made and uploaded.
    pub fit: Option<GyroFit>,
    /// Why there is none.
    pub not_fitted: Option<String>,
    /// Moves not used, each with its cause.
    pub dropped_moves: Vec<String>,
}

impl GyroJson {
    /// The gyro part of `calibration` (as uploaded) with what its fit gave.
    pub fn new(calibration: &CalibrationJson, outcome: &GyroOutcome) -> Self {
        GyroJson {
            matrix: calibration.gyro_matrix.unwrap_or(identity()),
            bias_dps: calibration.gyro_bias_dps.unwrap_or_default(),
            std_errors: outcome.fit.as_ref().map(|f| f.std_errors),
            turns: outcome.fit.as_ref().map_or(0, |f| f.turns),
            residual_deg: outcome.fit.as_ref().map(|f| f.residual_deg),
            not_fitted: outcome.not_fitted.clone(),
            dropped_moves: outcome.dropped_moves.clone(),
        }
    }
}

/// `truth.gyro`: the simulated sensor's true correction, w = matrix (w_raw - bias_dps).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TruthGyroJson {
    /// True G.
    pub matrix: Mat3<f32>,
    /// True bias at the truth's temperature, deg/s.
    pub bias_dps: Vec3<f32>,
}

/// The gyro's lines for a person: G's diagonal with standard errors, or why it was not fitted.
pub fn text(gyro: &GyroJson, check: Option<&TurnCheck>) -> String {
    let mut out = String::new();
    for dropped in &gyro.dropped_moves {
        out.push_str(&format!("gyro: {dropped}\n"));
    }
    match (&gyro.std_errors, &gyro.not_fitted) {
        (Some(e), _) => out.push_str(&format!(
            "gyro: G from {} turns, scale {:.5} +- {:.5}, {:.5} +- {:.5}, {:.5} +- {:.5}; residual {:.3} degrees\n",
            gyro.turns,
            gyro.matrix[0][0],
            e[0][0],
            gyro.matrix[1][1],
            e[1][1],
            gyro.matrix[2][2],
            e[2][2],
            gyro.residual_deg.unwrap_or(0.0)
        )),
        (None, Some(why)) => out.push_str(&format!("gyro: scale and misalignment not calibrated: {why}\n")),
        (None, None) => {}
    }
    if let Some(check) = check {
        out.push_str(&format!("{}\n", check.line()));
    }
    out
}

/// The session report's gyro figure: each turn's angle by the gyro minus the accelerometer's, raw
/// and calibrated, against the turn's number; raw alone, said so, when no G was fitted (the
/// "calibrated" angles are then the raw ones).
pub fn turns_figure(turns: &[TurnSummary]) -> Figure {
    let series = |name: &str, role, angle: fn(&TurnSummary) -> f64| Series {
        name: name.to_owned(),
        style: SeriesStyle::Points,
        role,
        points: turns.iter().enumerate().map(|(i, t)| [(i + 1) as f64, angle(t) - t.expected_deg]).collect(),
    };
    Figure {
        id: "gyro-turns",
        title: "Each turn between positions: the gyro's angle minus the accelerometer's".to_owned(),
        x_label: "turn".to_owned(),
        y_label: "gyro - accelerometer (degrees)".to_owned(),
        equal_axes: false,
        log_axes: false,
        index_x: true,
        series: match turns.iter().any(|t| t.calibrated_deg != t.raw_deg) {
            true => vec![
                series("raw gyro", Role::Raw, |t| t.raw_deg),
                series("calibrated gyro", Role::Calibrated, |t| t.calibrated_deg),
            ],
            false => vec![series("raw gyro (no G was fitted)", Role::Raw, |t| t.raw_deg)],
        },
    }
}

/// The gyro's line in the session's text report.
pub fn turns_line(turns: &[TurnSummary]) -> String {
    let rms = |f: fn(&TurnSummary) -> f64| {
        (turns.iter().map(|t| f(t).powi(2)).sum::<f64>() / turns.len().max(1) as f64).sqrt()
    };
    format!(
        "gyro turns: {}; gyro - accelerometer angle rms {:.3} degrees raw, {:.3} calibrated; residual rms {:.3} degrees raw, {:.3} calibrated",
        turns.len(),
        rms(|t| t.raw_deg - t.expected_deg),
        rms(|t| t.calibrated_deg - t.expected_deg),
        rms(|t| t.residual_raw_deg),
        rms(|t| t.residual_calibrated_deg)
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn turn(raw_deg: f64, calibrated_deg: f64) -> TurnSummary {
        TurnSummary {
            from: "+Z".into(),
            to: "+X".into(),
            expected_deg: 90.0,
            raw_deg,
            calibrated_deg,
            residual_raw_deg: 0.0,
            residual_calibrated_deg: 0.0,
        }
    }

    #[test]
    fn turns_without_a_fitted_g_show_no_calibrated_series() {
        let names =
            |turns: &[TurnSummary]| turns_figure(turns).series.iter().map(|s| s.name.clone()).collect::<Vec<_>>();
        assert_eq!(names(&[turn(91.2, 90.01), turn(88.9, 89.98)]), ["raw gyro", "calibrated gyro"]);
        assert_eq!(names(&[turn(91.2, 91.2), turn(88.9, 88.9)]), ["raw gyro (no G was fitted)"]);
    }
}
