//! `accelcal noise --json`: one object, per axis the deviation curve and the fitted terms in the usual
//! units (ug for the accelerometer, deg/s for the gyro), a `units` object naming each unit, what the
//! noise means for a calibration, and Kalibr's four numbers in continuous and discrete time.

use std::collections::BTreeMap;

use serde::Serialize;

use super::{AxisNoise, NoiseReport};
use crate::noise::text::{capture_limit_is_lower_bound, capture_limit_s, CAPTURE_SECONDS_SHOWN};

/// Micro-g per g.
pub const UG_PER_G: f64 = 1e6;
/// Standard gravity in m/s^2 per g (Kalibr takes SI units).
pub const STANDARD_GRAVITY: f64 = 9.80665;

/// One axis in the usual units.
#[derive(Serialize)]
struct AxisJson {
    tau_s: Vec<f64>,
    adev: Vec<f64>,
    adev_low: Vec<f64>,
    adev_high: Vec<f64>,
    white_noise_density: Option<f64>,
    bias_instability: Option<f64>,
    bias_instability_tau_s: Option<f64>,
    /// Whether the curve resolves the bias instability (else it is only what the fit left there).
    bias_instability_resolved: bool,
    random_walk: Option<f64>,
}

/// The unit of each number of one axis.
#[derive(Serialize)]
struct AxisUnits {
    tau_s: &'static str,
    adev: &'static str,
    adev_low: &'static str,
    adev_high: &'static str,
    white_noise_density: &'static str,
    bias_instability: &'static str,
    bias_instability_tau_s: &'static str,
    random_walk: &'static str,
}

const ACCEL_UNITS: AxisUnits = AxisUnits {
    tau_s: "s",
    adev: "ug",
    adev_low: "ug",
    adev_high: "ug",
    white_noise_density: "ug/sqrt(Hz)",
    bias_instability: "ug",
    bias_instability_tau_s: "s",
    random_walk: "ug/s/sqrt(Hz)",
};

const GYRO_UNITS: AxisUnits = AxisUnits {
    tau_s: "s",
    adev: "deg/s",
    adev_low: "deg/s",
    adev_high: "deg/s",
    white_noise_density: "deg/s/sqrt(Hz)",
    bias_instability: "deg/s",
    bias_instability_tau_s: "s",
    random_walk: "deg/s/s/sqrt(Hz)",
};

/// Kalibr's IMU noise numbers: the largest of the three axes of each sensor, in SI units.
#[derive(Serialize)]
struct KalibrJson {
    /// What the four numbers of each part are and in which unit.
    note: &'static str,
    continuous_time: KalibrNumbers,
    discrete_time: KalibrNumbers,
}

/// accelerometer_noise_density, accelerometer_random_walk, gyroscope_noise_density, gyroscope_random_walk.
#[derive(Serialize)]
struct KalibrNumbers {
    accelerometer_noise_density: f64,
    accelerometer_random_walk: f64,
    gyroscope_noise_density: f64,
    gyroscope_random_walk: f64,
}

/// What the noise means for the six-position captures.
#[derive(Serialize)]
struct CalibrationJson {
    /// Averaging time in seconds beyond which no accelerometer axis improves with a longer capture.
    capture_limit_s: Option<f64>,
    /// True when the deviation still fell at the longest averaging time analysed: the limit is at least that.
    capture_limit_is_lower_bound: bool,
    /// Capture lengths in seconds and the 1-sigma error of each accelerometer axis's mean, ug.
    accuracy_ug: Vec<(f64, [Option<f64>; 3])>,
}

/// The whole object.
#[derive(Serialize)]
struct NoiseJson {
    sample_rate_hz: f64,
    samples: usize,
    #[serde(flatten)]
    axes: BTreeMap<&'static str, AxisJson>,
    units: BTreeMap<&'static str, &'static AxisUnits>,
    /// Which of the two noise density conventions `white_noise_density` follows.
    white_noise_convention: &'static str,
    calibration: CalibrationJson,
    kalibr: Option<KalibrJson>,
}

/// The report as one pretty-printed JSON object.
pub fn render(report: &NoiseReport) -> String {
    let json = NoiseJson {
        sample_rate_hz: report.rate_hz,
        samples: report.samples,
        axes: report.axes.iter().map(|a| (a.name, axis_json(a))).collect(),
        units: report.axes.iter().map(|a| (a.name, if a.is_accel() { &ACCEL_UNITS } else { &GYRO_UNITS })).collect(),
        white_noise_convention: WHITE_NOISE_CONVENTION,
        calibration: calibration_json(report),
        kalibr: kalibr_json(report),
    };
    serde_json::to_string_pretty(&json).unwrap_or_default()
}

/// The factor from the axis's own unit to the usual one: g to ug, deg/s unchanged.
pub fn usual_scale(axis: &AxisNoise) -> f64 {
    if axis.is_accel() {
        UG_PER_G
    } else {
        1.0
    }
}

fn axis_json(axis: &AxisNoise) -> AxisJson {
    let scale = usual_scale(axis);
    let column = |f: fn(&super::AllanPoint) -> f64| axis.curve.iter().map(|p| f(p) * scale).collect();
    AxisJson {
        tau_s: axis.curve.iter().map(|p| p.tau_s).collect(),
        adev: column(|p| p.adev),
        adev_low: column(|p| p.adev_low),
        adev_high: column(|p| p.adev_high),
        white_noise_density: axis.terms.map(|t| t.white_noise_density() * scale),
        bias_instability: axis.terms.map(|t| t.bias_instability * scale),
        bias_instability_tau_s: axis.terms.map(|t| t.bias_instability_tau_s),
        bias_instability_resolved: axis.bias_instability_resolved(),
        random_walk: axis.terms.map(|t| t.random_walk * scale),
    }
}

fn calibration_json(report: &NoiseReport) -> CalibrationJson {
    let accuracy = |seconds: f64| {
        let mut axes = [None; 3];
        for (slot, axis) in axes.iter_mut().zip(report.axes.iter().filter(|a| a.is_accel())) {
            *slot = axis.terms.map(|t| t.adev(seconds) * UG_PER_G);
        }
        (seconds, axes)
    };
    CalibrationJson {
        capture_limit_s: capture_limit_s(report),
        capture_limit_is_lower_bound: capture_limit_is_lower_bound(report),
        accuracy_ug: CAPTURE_SECONDS_SHOWN.iter().map(|&s| accuracy(s)).collect(),
    }
}

fn kalibr_json(report: &NoiseReport) -> Option<KalibrJson> {
    let largest = |accel: bool, pick: fn(&super::NoiseTerms) -> f64| {
        report.axes.iter().filter(|a| a.is_accel() == accel).filter_map(|a| a.terms.as_ref().map(pick)).reduce(f64::max)
    };
    let to_rad = std::f64::consts::PI / 180.0;
    let continuous = KalibrNumbers {
        accelerometer_noise_density: largest(true, |t| t.white_noise_n)? * STANDARD_GRAVITY,
        accelerometer_random_walk: largest(true, |t| t.random_walk)? * STANDARD_GRAVITY,
        gyroscope_noise_density: largest(false, |t| t.white_noise_n)? * to_rad,
        gyroscope_random_walk: largest(false, |t| t.random_walk)? * to_rad,
    };
    let discrete = discrete_time(&continuous, report.rate_hz);
    Some(KalibrJson { note: KALIBR_NOTE, continuous_time: continuous, discrete_time: discrete })
}

/// See the NOTE in [`super::fit`].
const WHITE_NOISE_CONVENTION: &str = "white_noise_density is one-sided, as datasheets state it (rms noise = \
density * sqrt(bandwidth)); IEEE 952's N, the Allan deviation at 1 s, and kalibr.continuous_time are two-sided: \
white_noise_density / sqrt(2)";

const KALIBR_NOTE: &str = "continuous_time: what Kalibr's imu.yaml takes (two-sided, the Allan deviation at 1 s) (m/s^2/sqrt(Hz), m/s^3/sqrt(Hz), \
rad/s/sqrt(Hz), rad/s^2/sqrt(Hz)); discrete_time: per sample at sample_rate_hz (noise density * sqrt(rate): \
m/s^2, rad/s; random walk / sqrt(rate): m/s^2, rad/s), what a filter stepping at that rate adds each step";

/// Kalibr's discrete-time forms: sigma_d = sigma * sqrt(rate), sigma_bd = sigma_b / sqrt(rate).
fn discrete_time(continuous: &KalibrNumbers, rate_hz: f64) -> KalibrNumbers {
    let root = rate_hz.sqrt();
    KalibrNumbers {
        accelerometer_noise_density: continuous.accelerometer_noise_density * root,
        accelerometer_random_walk: continuous.accelerometer_random_walk / root,
        gyroscope_noise_density: continuous.gyroscope_noise_density * root,
        gyroscope_random_walk: continuous.gyroscope_random_walk / root,
    }
}
