//! `accelcal noise --json`: one object, per axis the deviation curve and the fitted terms in the usual
//! units (ug for the accelerometer, deg/s for the gyro), a `units` object naming each unit, what the
//! noise means for a calibration, and Kalibr's four numbers in continuous and discrete time. The one
//! schema of that object: `accelcal noise --json` writes it, the report, `calibrate --noise` and the
//! Kalibr export read it ([`read`]). Every part may be absent on reading (older reports, or only the
//! part a reader takes); each reader names what it lacks.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

pub use super::kalibr::{KalibrJson, KalibrNumbers};
use super::{
    capture_limit_is_lower_bound, capture_limit_s, resolved_unless_said, usual_scale, AxisNoise, NoiseReport, AXES,
    CAPTURE_SECONDS_SHOWN, UG_PER_G,
};

/// One axis in the usual units (ug for the accelerometer, deg/s for the gyro; `units` names them).
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(default)]
pub struct AxisJson {
    /// Averaging times, s.
    pub tau_s: Vec<f64>,
    /// The Allan deviation at each.
    pub adev: Vec<f64>,
    /// Its 68 % interval's lower end.
    pub adev_low: Vec<f64>,
    /// Its 68 % interval's upper end.
    pub adev_high: Vec<f64>,
    /// White noise density, one-sided as datasheets give it.
    pub white_noise_density: Option<f64>,
    /// Bias instability.
    pub bias_instability: Option<f64>,
    /// Where the fitted deviation is smallest, s.
    pub bias_instability_tau_s: Option<f64>,
    /// Whether the curve resolves the bias instability (else it is only what the fit left there;
    /// reports before the flag do not say: taken as resolved).
    #[serde(default = "resolved_unless_said")]
    pub bias_instability_resolved: bool,
    /// Random walk.
    pub random_walk: Option<f64>,
    /// Whether the curve resolves the random walk (else it is only what the fit left at the curve's
    /// end; reports before the flag do not say: taken as resolved).
    #[serde(default = "resolved_unless_said")]
    pub random_walk_resolved: bool,
}

/// The unit of each number of one axis.
#[derive(Debug, Serialize)]
pub struct AxisUnits {
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

/// What the noise means for the six-position captures.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(default)]
pub struct CaptureAdviceJson {
    /// Averaging time in seconds beyond which no accelerometer axis improves with a longer capture.
    pub capture_limit_s: Option<f64>,
    /// True when the deviation still fell at the longest averaging time analysed: the limit is at least that.
    pub capture_limit_is_lower_bound: bool,
    /// Capture lengths in seconds and the 1-sigma error of each accelerometer axis's mean, ug.
    pub accuracy_ug: Vec<(f64, [Option<f64>; 3])>,
}

/// The whole object `accelcal noise --json` prints.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(default)]
pub struct NoiseJson {
    /// The serial of the board recorded; null when the recording does not name it (a recording
    /// written before the board was kept, or a file of other origin).
    #[serde(default)]
    pub serial: Option<String>,
    /// Samples per second of the recording.
    pub sample_rate_hz: Option<f64>,
    /// Samples per axis.
    pub samples: Option<usize>,
    /// The six axes, each a key of the object.
    #[serde(flatten)]
    pub axes: AxesJson,
    /// The unit of each number of each axis (written, not read).
    #[serde(skip_deserializing)]
    pub units: BTreeMap<&'static str, &'static AxisUnits>,
    /// Which of the two noise density conventions `white_noise_density` follows (written, not read).
    #[serde(skip_deserializing)]
    pub white_noise_convention: &'static str,
    /// What the noise means for a calibration's captures.
    pub calibration: CaptureAdviceJson,
    /// Kalibr's numbers (absent when an axis has no fitted terms).
    pub kalibr: Option<KalibrJson>,
}

impl NoiseJson {
    /// The report in the usual units.
    pub fn of(report: &NoiseReport) -> Self {
        NoiseJson {
            serial: report.board.clone(),
            sample_rate_hz: Some(crate::shown::hz_value(report.rate_hz)),
            samples: Some(report.samples),
            axes: AxesJson::of(report),
            units: report
                .axes
                .iter()
                .map(|a| (a.name, if a.is_accel() { &ACCEL_UNITS } else { &GYRO_UNITS }))
                .collect(),
            white_noise_convention: WHITE_NOISE_CONVENTION,
            calibration: calibration_json(report),
            kalibr: super::kalibr::numbers(report),
        }
    }

    /// The axis called `name` (`accel_x` ... `gyro_z`); the reason when the report has none.
    pub fn axis(&self, name: &str) -> Result<&AxisJson, String> {
        let found = self.axes.all().into_iter().find(|(n, _)| *n == name).and_then(|(_, axis)| axis.as_ref());
        found.ok_or_else(|| format!("it has no {name}: is it `accelcal noise --json` output?"))
    }
}

/// The six axes of a noise report, each under its own name.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(default)]
pub struct AxesJson {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub accel_x: Option<AxisJson>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub accel_y: Option<AxisJson>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub accel_z: Option<AxisJson>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gyro_x: Option<AxisJson>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gyro_y: Option<AxisJson>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gyro_z: Option<AxisJson>,
}

impl AxesJson {
    /// Every axis of the report in the usual units.
    fn of(report: &NoiseReport) -> Self {
        let axis = |name: &str| report.axes.iter().find(|a| a.name == name).map(axis_json);
        let [accel_x, accel_y, accel_z, gyro_x, gyro_y, gyro_z] = AXES.map(axis);
        AxesJson { accel_x, accel_y, accel_z, gyro_x, gyro_y, gyro_z }
    }

    /// Each axis with its name, in [`AXES`] order.
    fn all(&self) -> [(&'static str, &Option<AxisJson>); 6] {
        let axes = [&self.accel_x, &self.accel_y, &self.accel_z, &self.gyro_x, &self.gyro_y, &self.gyro_z];
        std::array::from_fn(|k| (AXES[k], axes[k]))
    }
}

/// The report as one pretty-printed JSON object.
pub fn render(report: &NoiseReport) -> String {
    serde_json::to_string_pretty(&NoiseJson::of(report)).unwrap_or_default()
}

/// A noise report as `accelcal noise --json` wrote it; the reason when the text is not one.
pub fn read(text: &str) -> Result<NoiseJson, String> {
    serde_json::from_str(text).map_err(|e| format!("{e}; give the output of `accelcal noise RECORDING --json`"))
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
        random_walk_resolved: axis.random_walk_resolved(),
    }
}

fn calibration_json(report: &NoiseReport) -> CaptureAdviceJson {
    let accuracy = |seconds: f64| {
        let mut axes = [None; 3];
        for (slot, axis) in axes.iter_mut().zip(report.axes.iter().filter(|a| a.is_accel())) {
            *slot = axis.terms.map(|t| t.adev(seconds) * UG_PER_G);
        }
        (seconds, axes)
    };
    CaptureAdviceJson {
        capture_limit_s: capture_limit_s(report),
        capture_limit_is_lower_bound: capture_limit_is_lower_bound(report),
        accuracy_ug: CAPTURE_SECONDS_SHOWN.iter().map(|&s| accuracy(s)).collect(),
    }
}

/// See the NOTE in [`super::fit`].
const WHITE_NOISE_CONVENTION: &str = "white_noise_density is one-sided, as datasheets state it (rms noise = \
density * sqrt(bandwidth)); IEEE 952's N, the Allan deviation at 1 s, and kalibr.continuous_time are two-sided: \
white_noise_density / sqrt(2)";
