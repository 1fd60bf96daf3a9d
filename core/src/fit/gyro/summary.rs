//! One turn as a report shows it: its angle by the accelerometer, by the raw gyro and by the
//! calibrated one, and how far the integrated turn misses the pose after it, before and after G.

use nalgebra::{Matrix3, Vector3};
use serde::{Deserialize, Serialize};
use shared::linalg::Mat3;

use super::integrate::{rotate_up, turned_deg, Turn};

/// A turn between two positions, in degrees.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TurnSummary {
    /// The position before.
    pub from: String,
    /// The position after.
    pub to: String,
    /// The angle between the two poses' gravity directions (calibrated accelerometer): what a turn
    /// about a horizontal line measures.
    pub expected_deg: f64,
    /// The turn's angle by the raw gyro (bias removed).
    pub raw_deg: f64,
    /// The turn's angle by the calibrated gyro.
    pub calibrated_deg: f64,
    /// Angle between the gravity the raw turn predicts after it and the one measured there.
    pub residual_raw_deg: f64,
    /// The same with G.
    pub residual_calibrated_deg: f64,
}

/// The summary of `turn` from `from` to `to`, calibrated with `g`.
pub fn summarise_turn(turn: &Turn, g: &Mat3<f64>, from: &str, to: &str) -> TurnSummary {
    let g = mutant!("gyro-residual-g-untransposed", Matrix3::from(*g).transpose(), Matrix3::from(*g));
    let miss = |g: &Matrix3<f64>| rotate_up(turn, g).angle(&Vector3::from(turn.up_after)).to_degrees();
    TurnSummary {
        from: from.to_owned(),
        to: to.to_owned(),
        expected_deg: Vector3::from(turn.up_before).angle(&Vector3::from(turn.up_after)).to_degrees(),
        raw_deg: turned_deg(turn, &Matrix3::identity()),
        calibrated_deg: turned_deg(turn, &g),
        residual_raw_deg: miss(&Matrix3::identity()),
        residual_calibrated_deg: miss(&g),
    }
}
