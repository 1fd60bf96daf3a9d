//! The report's temperature section: the board's temperature model (from `accelcal thermal --json`,
//! given to `accelcal report --thermal`) and the learning bins it was fitted to, with a plot of the
//! accelerometer offset drift the model predicts against the drift each bin shows.

use serde::Serialize;
use shared::calibration::{drift, TemperatureModel};
use shared::linalg::{self, Vec3};

use super::figure::{axis_role, Figure, Role, Series, SeriesStyle};
use super::thermal::{ThermalBinJson, ThermalReport};

/// Points along each model curve.
const CURVE_POINTS: usize = 40;
/// Milli-g per g.
const MG_PER_G: f64 = 1000.0;

/// The temperature model and what it came from.
#[derive(Debug, Clone, Serialize)]
pub struct TemperatureSection {
    /// T_ref, the temperature the static calibration holds at, in degC.
    pub ref_temp_c: f64,
    /// Lowest and highest temperature learned, in degC.
    pub learned_c: [f64; 2],
    /// Polynomial order per accelerometer axis.
    pub accel_order: [usize; 3],
    /// Polynomial order per gyro axis.
    pub gyro_order: [usize; 3],
    /// Held-out RMS error of the accelerometer model, in mg.
    pub held_out_mg: f64,
    /// Whether the sensitivity's drift was fitted (several orientations).
    pub scale_fitted: bool,
    /// The model's offset drift per axis over the learned span, last minus first, in mg.
    pub offset_change_mg: [f64; 3],
    /// The model's gyro bias drift per axis over the learned span, in deg/s.
    pub gyro_bias_change_dps: [f64; 3],
    /// The bins the model was fitted to.
    pub bins: Vec<ThermalBinJson>,
}

impl TemperatureSection {
    /// The section of a thermal report; `Err` says why it has none to show.
    pub fn new(thermal: &ThermalReport) -> Result<(Self, Figure), String> {
        let model = thermal.calibration.temperature.ok_or("its calibration has no temperature model")?;
        if thermal.fit.points.is_empty() {
            return Err("it lists no learning bins (written by an older accelcal thermal: run it again)".into());
        }
        let [low, high] = thermal.fit.learned_c;
        let change = |c| linalg::sub(at(&model, c, high), at(&model, c, low));
        let f = &thermal.fit;
        let section = TemperatureSection {
            ref_temp_c: f64::from(model.ref_temp_c),
            learned_c: f.learned_c,
            accel_order: f.accel_order,
            gyro_order: f.gyro_order,
            held_out_mg: f.held_out_mg,
            scale_fitted: f.scale_fitted,
            offset_change_mg: linalg::scale(change(&model.offset_g), MG_PER_G),
            gyro_bias_change_dps: change(&model.gyro_bias_dps),
            bins: f.points.clone(),
        };
        let figure = offset_figure(thermal, &model)?;
        Ok((section, figure))
    }
}

/// `coefficients`' drift at `temp_c`, per axis, in the coefficients' unit.
fn at(model: &TemperatureModel, coefficients: &shared::calibration::TempCoefficients, temp_c: f64) -> Vec3<f64> {
    drift(coefficients, model.delta_c(temp_c as f32)).map(f64::from)
}

/// Offset drift against temperature: per axis the model's curve o(T) - o and, for each bin, the
/// reading less the gravity the model scales for that temperature and less the static offset.
fn offset_figure(thermal: &ThermalReport, model: &TemperatureModel) -> Result<Figure, String> {
    let inverse = linalg::inverse(&thermal.calibration.matrix).ok_or("its calibration matrix is singular")?;
    let [low, high] = thermal.fit.learned_c;
    let mut series = Vec::new();
    for k in 0..3 {
        let name = ["x", "y", "z"][k];
        let curve = (0..=CURVE_POINTS).map(|i| {
            let temp_c = low + (high - low) * i as f64 / CURVE_POINTS as f64;
            [temp_c, at(model, &model.offset_g, temp_c)[k] * MG_PER_G]
        });
        // NOTE: the bins first and the model in grey, so its line shows over the bins that lie on it.
        let bins = thermal.fit.points.iter().map(|bin| bin_drift_mg(thermal, model, &inverse, bin, k)).collect();
        series.push(Series::new(&format!("{name} bins"), axis_role(k), SeriesStyle::Points, bins));
        series.push(Series::new(&format!("{name} model"), Role::Reference, SeriesStyle::Line, curve.collect()));
    }
    Ok(offset_axes(series))
}

/// A bin's (temperature, offset drift on axis `k` in mg): its reading less the gravity the model
/// scales for its temperature and less the static offset.
fn bin_drift_mg(
    thermal: &ThermalReport,
    model: &TemperatureModel,
    inverse: &shared::linalg::Mat3<f64>,
    bin: &ThermalBinJson,
    k: usize,
) -> [f64; 2] {
    let gravity = linalg::mul_vec(inverse, bin.force_g)[k] * (1.0 + at(model, &model.scale, bin.temp_c)[k]);
    [bin.temp_c, (bin.accel_g[k] - gravity - thermal.calibration.offset[k]) * MG_PER_G]
}

fn offset_axes(series: Vec<Series>) -> Figure {
    Figure {
        id: "temperature",
        title: "accelerometer offset drift: the model's curve and the bins it was fitted to".into(),
        x_label: "die temperature (degC)".into(),
        y_label: "offset - static offset (mg)".into(),
        equal_axes: false,
        log_axes: false,
        index_x: false,
        series,
    }
}
