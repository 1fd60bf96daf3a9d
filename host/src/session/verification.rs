//! What a session's verification found: the calibration checked at fresh orientations.

use serde::{Deserialize, Serialize};

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
