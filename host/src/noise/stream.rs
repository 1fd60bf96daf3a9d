//! A sketch's raw stream as a noise recording: the longest still period of the stream, in g and
//! deg/s, at the rate its timestamps give (or `--rate`); a stream with neither is refused, since a
//! rate guessed would scale every noise term.

use super::input::NoiseInputError;
use super::RateSeries;
use crate::limits::NOISE_MIN_SAMPLES;
use crate::stream::{Segment, StillPeriods, StreamLog};

/// The longest still period of `log`, and the series the analysis takes from it.
pub fn longest_still(log: &StreamLog) -> Result<(Segment, RateSeries), NoiseInputError> {
    let rate = log.rate.ok_or(NoiseInputError::NoStreamRate)?;
    let gyro = log.gyro_dps().ok_or(NoiseInputError::NoStreamGyro)?;
    let accel = log.accel_g();
    let still = StillPeriods::of(log);
    let longest =
        still.segments.into_iter().max_by_key(|s| s.samples).ok_or(NoiseInputError::TooShort { samples: 0 })?;
    if longest.samples < NOISE_MIN_SAMPLES {
        return Err(NoiseInputError::TooShort { samples: longest.samples });
    }
    let mut axes: [Vec<f64>; 6] = Default::default();
    for i in longest.first..=longest.last {
        let values = accel[i].iter().chain(&gyro[i]);
        axes.iter_mut().zip(values).for_each(|(axis, &value)| axis.push(value));
    }
    Ok((longest, RateSeries { rate_hz: rate.hz, axes, board: None }))
}
