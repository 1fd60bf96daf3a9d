//! The report's Allan deviation section, from the JSON `accelcal noise --json` prints (given to
//! `accelcal report --noise`, or computed there from a recording): the fitted noise terms of each
//! axis and a log-log plot of the accelerometer's deviation with the fitted curve.

use serde::Serialize;

use super::figure::{axis_role, Figure, Series, SeriesStyle};
use crate::noise::json::{AxisJson, NoiseJson};
use crate::noise::{NoiseTerms, AXES};

/// The noise of the board, as the report shows it.
#[derive(Debug, Clone, Serialize)]
pub struct AllanSection {
    /// Samples per second of the recording analysed.
    pub sample_rate_hz: f64,
    /// Samples per axis.
    pub samples: u64,
    /// Averaging time beyond which no accelerometer axis improves with a longer capture, in s.
    pub capture_limit_s: Option<f64>,
    /// Whether that limit is only a lower bound (the deviation still fell at the longest averaging time).
    pub capture_limit_is_lower_bound: bool,
    /// The six axes in `accel_x` ... `gyro_z` order.
    pub axes: Vec<AllanAxis>,
}

/// One axis's fitted terms, in the units `accelcal noise --json` names.
#[derive(Debug, Clone, Serialize)]
pub struct AllanAxis {
    /// `accel_x` ... `gyro_z`.
    pub name: &'static str,
    /// White noise density, one-sided as datasheets give it (ug/sqrt(Hz), deg/s/sqrt(Hz)).
    pub white_noise_density: Option<f64>,
    /// Bias instability (ug, deg/s).
    pub bias_instability: Option<f64>,
    /// Where the fitted deviation is smallest, in s.
    pub bias_instability_tau_s: Option<f64>,
    /// Whether the curve resolves the bias instability (older noise reports do not say: taken as so).
    pub bias_instability_resolved: bool,
    /// Random walk (ug/s/sqrt(Hz), deg/s/s/sqrt(Hz)).
    pub random_walk: Option<f64>,
}

impl AllanSection {
    /// The section and its plot from a noise report's JSON; `Err` says what it lacks.
    pub fn new(noise: &NoiseJson) -> Result<(Self, Figure), String> {
        let axes =
            AXES.iter().map(|&name| Ok(AllanAxis::new(name, noise.axis(name)?))).collect::<Result<_, String>>()?;
        let section = AllanSection {
            sample_rate_hz: noise.sample_rate_hz.ok_or("it has no sample_rate_hz")?,
            samples: noise.samples.ok_or("it has no samples")? as u64,
            capture_limit_s: noise.calibration.capture_limit_s,
            capture_limit_is_lower_bound: noise.calibration.capture_limit_is_lower_bound,
            axes,
        };
        let figure = figure(noise, &section.axes[..3])?;
        Ok((section, figure))
    }
}

impl AllanAxis {
    fn new(name: &'static str, axis: &AxisJson) -> Self {
        AllanAxis {
            name,
            white_noise_density: axis.white_noise_density,
            bias_instability: axis.bias_instability,
            bias_instability_tau_s: axis.bias_instability_tau_s,
            bias_instability_resolved: axis.bias_instability_resolved,
            random_walk: axis.random_walk,
        }
    }
}

/// The accelerometer's deviation per axis (markers) and the fitted curve (a line), log-log, in ug.
fn figure(noise: &NoiseJson, accel: &[AllanAxis]) -> Result<Figure, String> {
    let mut series = Vec::new();
    for (k, axis) in accel.iter().enumerate() {
        let curve = noise.axis(axis.name)?;
        let (taus, adev) = (&curve.tau_s, &curve.adev);
        if taus.is_empty() || taus.len() != adev.len() {
            return Err(format!("{} has no deviation curve (tau_s and adev of one length)", axis.name));
        }
        let short = ["x", "y", "z"][k];
        let measured = taus.iter().zip(adev).map(|(t, a)| [*t, *a]).collect();
        series.push(Series::new(&format!("{short} deviation"), axis_role(k), SeriesStyle::Points, measured));
        if let Some(terms) = fitted(axis) {
            let curve = taus.iter().map(|&t| [t, terms.adev(t)]).collect();
            series.push(Series::new(&format!("{short} fitted"), axis_role(k), SeriesStyle::Line, curve));
        }
    }
    Ok(deviation_axes(series))
}

fn deviation_axes(series: Vec<Series>) -> Figure {
    Figure {
        id: "allan-deviation",
        title: "accelerometer Allan deviation and the fitted noise terms".into(),
        x_label: "averaging time (s)".into(),
        y_label: "Allan deviation (ug)".into(),
        equal_axes: false,
        log_axes: true,
        series,
    }
}

/// The fitted terms of an axis as the noise analysis models them (its N is the one-sided density
/// over sqrt(2), see `noise::fit`).
fn fitted(axis: &AllanAxis) -> Option<NoiseTerms> {
    Some(NoiseTerms {
        white_noise_n: axis.white_noise_density? / std::f64::consts::SQRT_2,
        bias_instability: axis.bias_instability?,
        bias_instability_tau_s: axis.bias_instability_tau_s?,
        random_walk: axis.random_walk?,
    })
}
