//! How long `calibrate` captures and how many positions it takes: the target accuracy, and where
//! the noise that sets each capture's length comes from.

use std::path::PathBuf;

use clap::Args;

use crate::limits::DEFAULT_TARGET_MG;
use crate::procedure::stop_rule::{noise_from_report, Noise, StopRule};
use crate::procedure::ProcedureError;

/// Verification positions of an adaptive session: enough for an RMS, each as long as the target needs.
pub const ADAPTIVE_VERIFY_POSITIONS: u8 = 3;
/// Verification positions with fixed capture lengths (the guided procedure's classic count).
pub const FIXED_VERIFY_POSITIONS: u8 = 6;

/// `calibrate`'s target and noise.
#[derive(Args, Clone, Debug)]
pub struct LengthArgs {
    /// The | |a| - 1 g | error wanted at a fresh orientation, in mg (0.05-10): positions stop
    /// when their mean is known well enough for it, the session when the fit predicts it.
    #[arg(long, default_value_t = DEFAULT_TARGET_MG, value_parser = target_mg)]
    pub target_mg: f64,
    /// A noise report (`accelcal noise RECORDING --json`): each capture's length from its white
    /// noise instead of from the scatter the board measures during the capture.
    #[arg(long, value_name = "NOISE.json")]
    pub noise_report: Option<PathBuf>,
}

impl LengthArgs {
    /// The stop rule of each capture at `rate_hz`.
    pub fn rule(&self, rate_hz: u16) -> Result<StopRule, ProcedureError> {
        let noise = match &self.noise_report {
            Some(path) => noise_from_report(path)?,
            None => Noise::Measured,
        };
        Ok(StopRule { target_mg: self.target_mg, noise, rate_hz })
    }
}

/// A target within 0.05-10 mg.
fn target_mg(text: &str) -> Result<f64, String> {
    let mg: f64 = text.parse().map_err(|_| format!("{text:?} is not a number of mg"))?;
    if (0.05..=10.0).contains(&mg) {
        Ok(mg)
    } else {
        Err(format!("{mg} mg is not in 0.05-10 mg (below 0.05 mg the sensor's drift, not its noise, sets the error)"))
    }
}
