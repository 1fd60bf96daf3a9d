//! What a session's verification found: the calibration checked at fresh orientations, and the
//! gyro's check turn.

use serde::{Deserialize, Serialize};

use crate::limits::CHIP_AGREEMENT_SIGMAS;

/// The errors at the verification orientations, in mg.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Verification {
    /// Orientations checked.
    pub positions: usize,
    /// RMS of | |m| - 1 g | with the raw readings.
    pub before_rms_mg: f64,
    /// RMS of | |a| - 1 g | with the calibration.
    pub after_rms_mg: f64,
    /// Largest | |a| - 1 g | with the calibration.
    pub after_max_mg: f64,
    /// The calibration's own error with the noise floor removed: sqrt(after_rms^2 - floor^2), 0 when
    /// the figure is within its noise.
    pub after_rms_without_noise_mg: f64,
    /// Largest difference between the chip's own corrected samples and the calibration applied to
    /// the raw capture, in mg: proof the chip applies what was verified (noise of 20 samples).
    pub on_chip_difference_mg: f64,
    /// RMS over the orientations of the noise each capture's mean carries in |a| (its samples'
    /// spread over the square root of their count, through the calibration), in mg: the floor below
    /// which `after_rms_mg` cannot resolve an error.
    #[serde(default)]
    pub noise_floor_mg: f64,
    /// The size of the noise the chip's 20-sample mean carries (its samples' spread over the square
    /// root of 20, through the calibration), at the orientation where it is largest, in mg: the
    /// scale `on_chip_difference_mg` is judged against.
    #[serde(default)]
    pub on_chip_noise_mg: f64,
    /// |m| - 1 g at each orientation with the raw readings, in mg.
    #[serde(default)]
    pub before_mg: Vec<f64>,
    /// |a| - 1 g at each orientation with the calibration, in mg.
    #[serde(default)]
    pub after_mg: Vec<f64>,
}

/// What the verification turn measured, in degrees.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TurnCheck {
    /// The turn's angle by the calibrated accelerometer (between the rests before and after).
    pub accel_deg: f64,
    /// Its standard uncertainty (the accelerometer's noise over the rests).
    pub accel_uncertainty_deg: f64,
    /// The same tilt by the calibrated gyro: the rest before's up carried through the integrated turn.
    pub gyro_deg: f64,
    /// Its standard uncertainty: the rate noise integrated, and G's standard errors along the turn.
    pub gyro_uncertainty_deg: f64,
    /// The same turn through the raw gyro (bias removed, G undone), when G was fitted.
    pub raw_deg: Option<f64>,
}

impl TurnCheck {
    /// The line shown to the user.
    pub fn line(&self) -> String {
        let raw = self
            .raw_deg
            .map_or(" (the gyro's scale is not calibrated: the uncertainty is its noise alone)".to_owned(), |r| {
                format!(" (uncalibrated {r:.2})")
            });
        format!(
            "gyro check: a {:.2} +- {:.2} degree turn (by the accelerometer) now reads {:.2} +- {:.2} degrees{raw}",
            self.accel_deg, self.accel_uncertainty_deg, self.gyro_deg, self.gyro_uncertainty_deg
        )
    }
}

/// The errors at one fresh orientation, in mg.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Check {
    /// |m| - 1 g with the raw reading.
    pub before_mg: f64,
    /// |a| - 1 g with the calibration.
    pub after_mg: f64,
    /// The noise of |a| of the reading's mean.
    pub noise_mg: f64,
    /// The chip's corrected mean minus the host's correction (0 where no chip applies it).
    pub on_chip_mg: f64,
    /// The noise of the chip's mean it is judged against (0 where no chip applies it).
    pub on_chip_noise_mg: f64,
}

impl Verification {
    /// What the checks at `checks` found.
    pub fn of(checks: &[Check]) -> Self {
        let rms = |pick: fn(&Check) -> f64| {
            (checks.iter().map(|c| pick(c).powi(2)).sum::<f64>() / checks.len().max(1) as f64).sqrt()
        };
        let (after, floor) = (rms(|c| c.after_mg), rms(|c| c.noise_mg));
        Verification {
            positions: checks.len(),
            before_rms_mg: rms(|c| c.before_mg),
            after_rms_mg: after,
            after_rms_without_noise_mg: (after * after - floor * floor).max(0.0).sqrt(),
            after_max_mg: checks
                .iter()
                .fold(0.0, |m, c| m.max(mutant!("worst-error-signed", c.after_mg.abs(), c.after_mg))),
            on_chip_difference_mg: checks.iter().fold(0.0, |m, c| m.max(c.on_chip_mg)),
            on_chip_noise_mg: checks.iter().fold(0.0, |m, c| m.max(c.on_chip_noise_mg)),
            noise_floor_mg: floor,
            before_mg: checks.iter().map(|c| c.before_mg).collect(),
            after_mg: checks.iter().map(|c| c.after_mg).collect(),
        }
    }
}

/// Corrected samples the chip averages to compare its correction with the host's.
pub const CHIP_SAMPLES: u32 = 20;

impl Verification {
    /// Whether the chip's corrected samples agree with the host's correction, judged against the
    /// noise of the chip's 20-sample mean, in words.
    pub fn chip_agreement(&self) -> String {
        let (difference, noise) = (self.on_chip_difference_mg, self.on_chip_noise_mg);
        if difference <= CHIP_AGREEMENT_SIGMAS * noise {
            format!("chip and host agree: they differ by {difference:.2} mg, within {CHIP_AGREEMENT_SIGMAS} times the {noise:.2} mg noise of the chip's {CHIP_SAMPLES}-sample mean")
        } else {
            format!("chip and host differ by {difference:.2} mg, more than {CHIP_AGREEMENT_SIGMAS} times the {noise:.2} mg noise of the chip's {CHIP_SAMPLES}-sample mean: the chip does not apply the calibration verified")
        }
    }
}
