//! A stream's calibration checked at its fresh orientations: the still periods held out of the fit
//! (away from every face and corner), | |m| - 1 g | raw and | |a| - 1 g | calibrated, each against
//! the noise of its mean, as a verification of accelcal's own boards is judged.

use shared::linalg::{mul_vec, norm, scale, sub, transpose};

use crate::data::Row;
use crate::fit::Fit;
use crate::session::{Check, Verification};

/// The fit checked at the held-out rows (means in the stream's unit, `per_g` of it a g); `None`
/// when none was held out.
pub fn verification(fit: &Fit, held_out: &[Row], per_g: f64) -> Option<Verification> {
    if held_out.is_empty() {
        return None;
    }
    let checks: Vec<Check> = held_out.iter().map(|row| check(fit, row, per_g)).collect();
    Some(Verification::of(&checks))
}

/// One fresh orientation. NOTE: no chip applies a stream's calibration: the on-chip terms are 0.
fn check(fit: &Fit, row: &Row, per_g: f64) -> Check {
    let corrected = mul_vec(&fit.matrix, sub(row.reading, fit.offset));
    Check {
        before_mg: (norm(row.reading) / per_g - 1.0) * 1e3,
        after_mg: (norm(corrected) - 1.0) * 1e3,
        noise_mg: norm_noise_g(fit, row, corrected) * 1e3,
        on_chip_mg: 0.0,
        on_chip_noise_mg: 0.0,
    }
}

/// The standard deviation of |a| of the row's mean, in g: its samples' scatter along gravity,
/// through the calibration, over the square root of their count (samples taken as independent).
fn norm_noise_g(fit: &Fit, row: &Row, corrected: [f64; 3]) -> f64 {
    let along = mul_vec(&transpose(&fit.matrix), scale(corrected, 1.0 / norm(corrected).max(f64::MIN_POSITIVE)));
    let (std, samples) = (row.std.unwrap_or([0.0; 3]), f64::from(row.count.unwrap_or(1).max(1)));
    ((0..3).map(|k| (along[k] * std[k]).powi(2)).sum::<f64>() / samples).sqrt()
}
