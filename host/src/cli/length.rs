//! How long `calibrate` captures and how many positions it takes: the target accuracy, and where
//! the noise that sets each capture's length comes from.

use super::args::LengthArgs;
use crate::limits::{DEFAULT_TARGET_MG, QUICK_TARGET_MG};
use crate::procedure::stop_rule::{noise_from_report, Noise, StopRule};
use crate::procedure::ProcedureError;

pub use accelcal_core::run::board::ADAPTIVE_VERIFY_POSITIONS;

impl LengthArgs {
    /// The target asked for: `--target-mg`, else `--quick`'s, else the default.
    pub fn target_mg(&self) -> f64 {
        self.target_mg.unwrap_or(if self.quick { QUICK_TARGET_MG } else { DEFAULT_TARGET_MG })
    }

    /// The stop rule of each capture at `rate_hz`.
    pub fn rule(&self, rate_hz: u16) -> Result<StopRule, ProcedureError> {
        let noise = match &self.noise_report {
            Some(path) => {
                let unreadable =
                    |e: std::io::Error| ProcedureError::NoiseReport { path: path.clone(), reason: e.to_string() };
                noise_from_report(path, &std::fs::read_to_string(path).map_err(unreadable)?)?
            }
            None => Noise::Measured,
        };
        Ok(StopRule { target_mg: self.target_mg(), noise, rate_hz })
    }
}
