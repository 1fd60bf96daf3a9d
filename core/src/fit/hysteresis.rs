//! Heating against cooling: whether the accelerometer offset at a temperature depends on the way the
//! board came to it. Each segment's bins are fitted alone, where both segments overlap, with a
//! quadratic in temperature around the overlap's middle; the difference of the two fits there is
//! reported with its standard error from each fit's residual scatter.

use nalgebra::{Matrix3, Vector3};
use serde::{Deserialize, Serialize};
use shared::calibration::{drift, TemperatureModel};
use shared::linalg::{self, Mat3};

use super::thermal::ThermalPoint;
use crate::limits::MIN_HYSTERESIS_OVERLAP_C;

/// Milli-g per g.
const MG_PER_G: f64 = 1000.0;

/// The offset of the heating segment less that of the cooling one, at one temperature.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Hysteresis {
    /// Where the segments are compared: the middle of their overlap, in degC.
    pub temp_c: f64,
    /// The overlap both segments cover, in degC.
    pub overlap_c: [f64; 2],
    /// Heating minus cooling offset per axis, in mg.
    pub heating_minus_cooling_mg: [f64; 3],
    /// Its standard error per axis, in mg.
    pub std_error_mg: [f64; 3],
    /// Bins of each segment inside the overlap: heating, cooling.
    pub bins: [usize; 2],
}

/// Compares the `heating` and `cooling` bins around the static `matrix` and the fitted `model` (which
/// removes gravity's share of each reading); `None` when they overlap by less than
/// [`MIN_HYSTERESIS_OVERLAP_C`] or either has too few bins there for a quadratic with scatter.
pub fn compare(
    model: &TemperatureModel,
    matrix: &Mat3<f64>,
    heating: &[ThermalPoint],
    cooling: &[ThermalPoint],
) -> Option<Hysteresis> {
    let overlap = overlap_c(heating, cooling).filter(|[low, high]| high - low >= MIN_HYSTERESIS_OVERLAP_C)?;
    let temp_c = (overlap[0] + overlap[1]) / 2.0;
    let inside = |points: &[ThermalPoint]| -> Vec<ThermalPoint> {
        points.iter().filter(|p| (overlap[0]..=overlap[1]).contains(&p.temp_c)).copied().collect()
    };
    let (heating, cooling) = (inside(heating), inside(cooling));
    let inverse = linalg::inverse(matrix)?;
    let mut difference = [0.0; 3];
    let mut std_error = [0.0; 3];
    for k in 0..3 {
        let offsets = |points: &[ThermalPoint]| apparent_offsets(model, &inverse, points, k);
        let (h, c) = (level_at(&offsets(&heating), temp_c)?, level_at(&offsets(&cooling), temp_c)?);
        difference[k] = (h.0 - c.0) * MG_PER_G;
        std_error[k] = (h.1 * h.1 + c.1 * c.1).sqrt() * MG_PER_G;
    }
    let bins = [heating.len(), cooling.len()];
    Some(Hysteresis { temp_c, overlap_c: overlap, heating_minus_cooling_mg: difference, std_error_mg: std_error, bins })
}

/// The temperatures both segments cover, lowest and highest.
fn overlap_c(heating: &[ThermalPoint], cooling: &[ThermalPoint]) -> Option<[f64; 2]> {
    let span = |points: &[ThermalPoint]| {
        points.iter().fold((f64::MAX, f64::MIN), |(low, high), p| (low.min(p.temp_c), high.max(p.temp_c)))
    };
    let ((h_low, h_high), (c_low, c_high)) = (span(heating), span(cooling));
    Some([h_low.max(c_low), h_high.min(c_high)]).filter(|[low, high]| low <= high)
}

/// Each bin's (temperature, offset on axis `k`): its reading less gravity's share, scaled by the
/// model's sensitivity at that temperature, in g.
fn apparent_offsets(
    model: &TemperatureModel,
    inverse: &Mat3<f64>,
    points: &[ThermalPoint],
    k: usize,
) -> Vec<(f64, f64)> {
    points
        .iter()
        .map(|p| {
            let scale = 1.0 + f64::from(drift(&model.scale, model.delta_c(p.temp_c as f32))[k]);
            (p.temp_c, p.accel_g[k] - linalg::mul_vec(inverse, p.force_g)[k] * scale)
        })
        .collect()
}

/// The least-squares quadratic through `points` evaluated at `temp_c`, and its standard error; `None`
/// with fewer than five points or a singular fit.
fn level_at(points: &[(f64, f64)], temp_c: f64) -> Option<(f64, f64)> {
    if points.len() < 5 {
        return None;
    }
    let row = |t: f64| Vector3::new(1.0, t - temp_c, (t - temp_c).powi(2));
    let mut normal = Matrix3::zeros();
    let mut rhs = Vector3::zeros();
    for &(t, y) in points {
        normal += row(t) * row(t).transpose();
        rhs += row(t) * y;
    }
    let inverse = normal.try_inverse()?;
    let coefficients = inverse * rhs;
    let squares: f64 = points.iter().map(|&(t, y)| (y - row(t).dot(&coefficients)).powi(2)).sum();
    let variance = squares / (points.len() - 3) as f64;
    // NOTE: at t = temp_c the row is (1, 0, 0): the level is the constant term.
    Some((coefficients[0], (variance * inverse[(0, 0)]).sqrt()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use shared::calibration::MAX_TEMP_ORDER;

    /// Bins of a board resting on +z and -x alternately, its offset drifting 1 mg/degC on every axis,
    /// `shift_mg` more on the way down, with a deterministic +-0.05 mg scatter.
    fn segment(temps: impl Iterator<Item = f64>, shift_mg: f64) -> Vec<ThermalPoint> {
        temps
            .enumerate()
            .map(|(i, t)| {
                let force_g = if i % 2 == 0 { [0.0, 0.0, 1.0] } else { [-1.0, 0.0, 0.0] };
                let wiggle = if i % 3 == 0 { 0.05e-3 } else { -0.025e-3 };
                let offset = 1e-3 * (t - 25.0) + shift_mg * 1e-3 + wiggle;
                ThermalPoint { temp_c: t, force_g, accel_g: force_g.map(|f| f + offset), gyro_dps: [0.0; 3] }
            })
            .collect()
    }

    fn compared(shift_mg: f64) -> Hysteresis {
        let model = TemperatureModel { scale: [[0.0; 3]; MAX_TEMP_ORDER], ..TemperatureModel::flat(25.0) };
        let heating = segment((0..35).map(|i| 13.0 + i as f64), 0.0);
        let cooling = segment((0..30).map(|i| 45.5 - i as f64), shift_mg);
        compare(&model, &linalg::identity(), &heating, &cooling).expect("they overlap")
    }

    #[test]
    fn a_shift_on_the_way_down_is_found_within_its_standard_error() {
        let found = compared(0.4);
        assert!((found.temp_c - 31.0).abs() < 1e-9, "{found:?}");
        for k in 0..3 {
            let (difference, error) = (found.heating_minus_cooling_mg[k], found.std_error_mg[k]);
            assert!(error > 0.005 && error < 0.05, "axis {k}: standard error {error} mg");
            assert!((difference + 0.4).abs() < 3.0 * error, "axis {k}: {difference} +- {error} mg, truth -0.4");
        }
        let none = compared(0.0);
        assert!(
            none.heating_minus_cooling_mg.iter().zip(none.std_error_mg).all(|(d, e)| d.abs() < 3.0 * e),
            "{none:?}"
        );
    }

    #[test]
    fn segments_that_barely_overlap_are_not_compared() {
        let model = TemperatureModel::flat(25.0);
        let heating = segment((0..10).map(|i| 13.0 + i as f64), 0.0);
        let cooling = segment((0..10).map(|i| 40.0 - i as f64), 0.0);
        assert_eq!(compare(&model, &linalg::identity(), &heating, &cooling), None);
    }
}
