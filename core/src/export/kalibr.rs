//! Kalibr's imu.yaml: the four noise terms (continuous time) and the rate, from `accelcal noise --json`.
//! Kalibr takes no calibration matrix here: the calibration is stated for the data it is given.

use super::loss::{diagonal, loss, Carried};
use super::source::Noise;
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
    lossy: true,
};

/// The imu.yaml.
pub fn kalibr(source: &Source) -> Result<Export, ExportError> {
    let noise = source.noise.as_ref().ok_or(ExportError::NeedsNoise)?;
    if let (Some(calibrated), Some(recorded)) = (&source.serial, &noise.serial) {
        if calibrated != recorded {
            return Err(ExportError::NoiseOfAnotherBoard {
                calibrated: calibrated.clone(),
                recorded: recorded.clone(),
            });
        }
    }
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
    let mut lines = lines(source, &KALIBR_SAID, &loss);
    lines.extend(unresolved(noise));
    Ok(text(lines, &HASH, &body, loss))
}

/// A line for each random walk the recording did not resolve: its number is a bound, not a measure.
fn unresolved(noise: &Noise) -> Vec<String> {
    let sensors = ["accelerometer", "gyroscope"].into_iter().zip(noise.random_walks_resolved);
    sensors
        .filter(|(_, resolved)| !resolved)
        .map(|(sensor, _)| {
            format!(
                "{sensor}_random_walk: not resolved by the recording: the largest its longest averaging time allows \
                 (sigma(tau) sqrt(3 / tau)); record for hours, still, to measure it"
            )
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn with_noise(resolved: [bool; 2], calibrated: Option<&str>, recorded: Option<&str>) -> Source {
        let session = crate::sim::sessions::adaptive(1, 0.0, 0.004);
        let mut source = Source::from_session(&session, "s.json").unwrap();
        source.serial = calibrated.map(str::to_owned);
        source.noise = Some(Noise {
            accel_noise_density: 1.5e-3,
            accel_random_walk: 2e-4,
            gyro_noise_density: 8e-5,
            gyro_random_walk: 3e-6,
            rate_hz: 1000.0,
            random_walks_resolved: resolved,
            serial: recorded.map(str::to_owned),
        });
        source
    }

    #[test]
    fn a_random_walk_the_recording_did_not_resolve_is_stated_as_a_bound() {
        let text = |resolved| String::from_utf8(kalibr(&with_noise(resolved, None, None)).unwrap().bytes).unwrap();
        let accel_only = text([false, true]);
        assert!(accel_only.contains("accelerometer_random_walk: not resolved by the recording"), "{accel_only}");
        assert!(!accel_only.contains("gyroscope_random_walk: not resolved"), "{accel_only}");
        assert!(!text([true, true]).contains("not resolved"));
    }

    #[test]
    fn another_board_s_noise_report_is_refused() {
        let refused = kalibr(&with_noise([true; 2], Some("B1"), Some("B2"))).unwrap_err().to_string();
        assert!(refused.contains("recorded on board B2") && refused.contains("board B1's"), "{refused}");
        assert!(kalibr(&with_noise([true; 2], Some("B1"), Some("B1"))).is_ok());
        assert!(kalibr(&with_noise([true; 2], Some("B1"), None)).is_ok(), "a report that names no board is taken");
    }
}
