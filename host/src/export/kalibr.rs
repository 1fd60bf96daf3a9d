//! Kalibr's imu.yaml: the four noise terms (continuous time) and the rate, from `accelcal noise --json`.
//! Kalibr takes no calibration matrix here: the calibration is stated for the data it is given.

use super::loss::{diagonal, loss, Carried};
use super::statement::{lines, Said};
use super::{text, Export, ExportError, Source, HASH};

const CONVENTION: &[&str] = &[
    "Kalibr imu.yaml: noise densities in m/s^2/sqrt(Hz) and rad/s/sqrt(Hz), random walks in m/s^3/sqrt(Hz) and rad/s^2/sqrt(Hz)",
    "continuous time, two-sided (the Allan deviation at 1 s), the largest of the three axes, as accelcal noise --json gives them",
    "no calibration is carried: apply accelcal's (e.g. --to c) to the data you record for Kalibr, or the loss below stays",
];

const KALIBR_SAID: Said = Said {
    title: "Kalibr (imu.yaml)",
    convention: CONVENTION,
    carries: "the noise terms only; none of the calibration",
    temperature: "not carried",
};

/// The imu.yaml.
pub fn kalibr(source: &Source) -> Result<Export, ExportError> {
    let noise = source.noise.ok_or(ExportError::NeedsNoise)?;
    let full = source.full();
    let nothing = Carried {
        matrix: diagonal([1.0; 3]),
        offset_g: [0.0; 3],
        gyro_matrix: diagonal([1.0; 3]),
        gyro_bias_dps: None,
    };
    let loss = loss(&full, &nothing);
    let body = format!(
        "accelerometer_noise_density: {:e}\naccelerometer_random_walk: {:e}\n\
         gyroscope_noise_density: {:e}\ngyroscope_random_walk: {:e}\nrostopic: /imu0\nupdate_rate: {}\n",
        noise.accel_noise_density,
        noise.accel_random_walk,
        noise.gyro_noise_density,
        noise.gyro_random_walk,
        noise.rate_hz
    );
    Ok(text(lines(source, &KALIBR_SAID, &loss), &HASH, &body, loss))
}
