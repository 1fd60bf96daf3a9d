//! Kalibr's four IMU noise numbers, as `accelcal noise --json` writes them under `kalibr` and the
//! Kalibr export reads them: continuous time (what imu.yaml takes) and discrete time, in SI units.

use serde::{Deserialize, Serialize};

use shared::STANDARD_GRAVITY;

use super::resolved_unless_said;
use super::{AxisNoise, NoiseReport};

/// Kalibr's IMU noise numbers: the largest of the three axes of each sensor, in SI units.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct KalibrJson {
    /// What the four numbers of each part are and in which unit (written, not read).
    #[serde(skip_deserializing)]
    pub note: &'static str,
    /// What Kalibr's imu.yaml takes.
    pub continuous_time: KalibrNumbers,
    /// Per sample at `sample_rate_hz` (a reader may leave it out).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub discrete_time: Option<KalibrNumbers>,
    /// Whether the recording resolves the accelerometer's random walk on every axis; where it does
    /// not, the number is the bound the curve allows (reports before the flag: taken as resolved).
    #[serde(default = "resolved_unless_said")]
    pub accelerometer_random_walk_resolved: bool,
    /// The same for the gyro.
    #[serde(default = "resolved_unless_said")]
    pub gyroscope_random_walk_resolved: bool,
}

/// accelerometer_noise_density, accelerometer_random_walk, gyroscope_noise_density, gyroscope_random_walk.
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
pub struct KalibrNumbers {
    pub accelerometer_noise_density: f64,
    pub accelerometer_random_walk: f64,
    pub gyroscope_noise_density: f64,
    pub gyroscope_random_walk: f64,
}

/// Kalibr's numbers of `report`: the largest of each sensor's axes; `None` when an axis has no
/// fitted terms.
pub(super) fn numbers(report: &NoiseReport) -> Option<KalibrJson> {
    let axes = |accel: bool| report.axes.iter().filter(move |a| a.is_accel() == accel);
    let largest = |accel: bool, pick: fn(&AxisNoise) -> Option<f64>| axes(accel).filter_map(pick).reduce(f64::max);
    let white = |a: &AxisNoise| a.terms.map(|t| t.white_noise_n);
    let to_rad = std::f64::consts::PI / 180.0;
    let continuous = KalibrNumbers {
        accelerometer_noise_density: largest(true, white)? * STANDARD_GRAVITY,
        accelerometer_random_walk: largest(true, AxisNoise::random_walk_or_bound)? * STANDARD_GRAVITY,
        gyroscope_noise_density: largest(false, white)? * to_rad,
        gyroscope_random_walk: largest(false, AxisNoise::random_walk_or_bound)? * to_rad,
    };
    let discrete = discrete_time(&continuous, report.rate_hz);
    Some(KalibrJson {
        note: KALIBR_NOTE,
        continuous_time: continuous,
        discrete_time: Some(discrete),
        accelerometer_random_walk_resolved: axes(true).all(AxisNoise::random_walk_resolved),
        gyroscope_random_walk_resolved: axes(false).all(AxisNoise::random_walk_resolved),
    })
}

const KALIBR_NOTE: &str = "continuous_time: what Kalibr's imu.yaml takes (two-sided, the Allan deviation at 1 s) (m/s^2/sqrt(Hz), m/s^3/sqrt(Hz), \
rad/s/sqrt(Hz), rad/s^2/sqrt(Hz)); a random walk the recording does not resolve (*_random_walk_resolved false) is \
the largest the curve allows, sigma(tau) sqrt(3 / tau) at its longest averaging time (68 % upper end): Kalibr is \
better told too much noise than a bias that never moves; discrete_time: per sample at sample_rate_hz (noise density * sqrt(rate): \
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
