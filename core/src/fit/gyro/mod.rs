//! The gyro's scale and misalignment from the turns between still poses (no turntable): each turn,
//! integrated through a candidate correction G, must carry the gravity direction the calibrated
//! accelerometer measured at one pose onto the one it measured at the next (the method of Tedaldi
//! et al. 2014, imu_tk; our own code). Calibrated rate: w = G (w_raw - b).

mod integrate;
mod observability;
mod solve;
mod summary;

use std::fmt;

use serde::Serialize;
use shared::linalg::{Mat3, Vec3};

use crate::limits::MIN_GYRO_TURNS;
pub use integrate::{rotate_up, turned_deg, Turn};
pub use observability::informative_turn_deg;
pub use solve::fit_gyro;
pub use summary::{summarise_turn, TurnSummary};

/// A fitted gyro correction.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GyroFit {
    /// G in w = G (w_raw - b), dimensionless, rows by calibrated axis.
    pub matrix: Mat3<f64>,
    /// Standard error of each entry of G.
    pub std_errors: Mat3<f64>,
    /// Root-mean-square angle, in degrees, between predicted and measured gravity after each turn.
    pub residual_deg: f64,
    /// Turns the fit used.
    pub turns: usize,
}

/// Why the gyro matrix cannot be fitted, with the way out.
#[derive(Debug, Clone, PartialEq)]
pub enum GyroFitError {
    /// Fewer turns than the fit needs.
    TooFewTurns { turns: usize },
    /// A gyro axis turned too little except about the vertical (such turns carry no information).
    Unobservable { axes: Vec<usize>, turned_deg: Vec3<f64> },
    /// The normal equations are singular or the iteration diverged.
    Diverged,
}

impl fmt::Display for GyroFitError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            GyroFitError::TooFewTurns { turns } => {
                write!(f, "only {turns} usable turns between positions; the gyro fit needs {MIN_GYRO_TURNS}: turn the board from face to face between the positions (a full calibration, without --chip-fit, has 13)")
            }
            GyroFitError::Unobservable { axes, turned_deg } => write!(f, "{}", observability::advice(axes, turned_deg)),
            GyroFitError::Diverged => write!(f, "the gyro fit did not converge: the turns do not agree with the positions (was the board moved during a capture?)"),
        }
    }
}

impl std::error::Error for GyroFitError {}

#[cfg(test)]
mod tests;
