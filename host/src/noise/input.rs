//! Reading a still recording for the noise analysis: a `.npy` recording as `accelcal record`
//! writes it (told by its magic), or CSV as `accelcal stream` writes it (columns
//! `ax_g,ay_g,az_g,gx_dps,gy_dps,gz_dps`, others ignored), sampled at a rate the caller names
//! (a recording names its own).

use std::io::Read;
use std::path::Path;

use shared::protocol::Sample;

use super::RateSeries;
use crate::recording::{self, read::is_npy, RecordingError};

/// The six columns the analysis needs, in [`super::AXES`] order.
pub const COLUMNS: [&str; 6] = ["ax_g", "ay_g", "az_g", "gx_dps", "gy_dps", "gz_dps"];

/// Fewest samples for an Allan deviation curve worth fitting (ten averaging times from 1 to N / 10).
pub const MIN_SAMPLES: usize = 100;

/// Why a recording cannot be analysed.
#[derive(Debug, thiserror::Error)]
pub enum NoiseInputError {
    #[error("cannot read {path}: {source}")]
    Io { path: String, source: std::io::Error },
    #[error("line 1: the header lacks column {column}; a recording has {}", COLUMNS.join(","))]
    MissingColumn { column: &'static str },
    #[error("line {line}: {reason}")]
    BadLine { line: usize, reason: String },
    #[error("{samples} samples is too few for an Allan deviation: record at least {MIN_SAMPLES}")]
    TooShort { samples: usize },
    #[error(transparent)]
    Recording(#[from] RecordingError),
    #[error("the stream has no timestamps, so its rate is unknown and every noise term would scale with a guess: give --rate (samples per second)")]
    NoStreamRate,
    #[error(
        "the stream has no gyro; the noise analysis takes both sensors (a recording of accelcal's own stream has them)"
    )]
    NoStreamGyro,
    #[error("--rate must be a positive number of samples per second, got {rate_hz}")]
    BadRate { rate_hz: f64 },
    #[error("--rate {given_hz} differs from the {recorded_hz} Hz the recording was taken at; leave --rate out")]
    RateDiffers { given_hz: f64, recorded_hz: f64 },
}

/// Sample rate of a CSV file when the caller names none, in Hz: the sensor's full rate.
pub const CSV_DEFAULT_RATE_HZ: f64 = 1000.0;

/// Reads a recording file: a `.npy` recording at the rate it names (`rate_hz`, when given, must
/// agree), a CSV file at `rate_hz` or [`CSV_DEFAULT_RATE_HZ`].
pub fn read_path(path: &Path, rate_hz: Option<f64>) -> Result<RateSeries, NoiseInputError> {
    let io = |source| NoiseInputError::Io { path: path.display().to_string(), source };
    let mut file = std::fs::File::open(path).map_err(io)?;
    let mut magic = [0u8; 6];
    let opened = file.read(&mut magic).map_err(io)?;
    if is_npy(&magic[..opened]) {
        let recording = recording::read_path(path)?;
        let recorded_hz = f64::from(recording.rate_hz);
        if rate_hz.is_some_and(|given| given != recorded_hz) {
            return Err(NoiseInputError::RateDiffers { given_hz: rate_hz.unwrap_or_default(), recorded_hz });
        }
        return from_samples(&recording.samples, recorded_hz);
    }
    read_csv(std::fs::File::open(path).map_err(io)?, rate_hz.unwrap_or(CSV_DEFAULT_RATE_HZ))
}

/// The six axes of recorded samples taken at `rate_hz`.
pub fn from_samples(samples: &[Sample], rate_hz: f64) -> Result<RateSeries, NoiseInputError> {
    check_rate(rate_hz)?;
    let mut axes: [Vec<f64>; 6] = Default::default();
    for sample in samples {
        let values = sample.accel_g.iter().chain(&sample.gyro_dps);
        axes.iter_mut().zip(values).for_each(|(axis, &value)| axis.push(f64::from(value)));
    }
    check_length(RateSeries { rate_hz, axes })
}

fn check_rate(rate_hz: f64) -> Result<(), NoiseInputError> {
    match rate_hz > 0.0 && rate_hz.is_finite() {
        true => Ok(()),
        false => Err(NoiseInputError::BadRate { rate_hz }),
    }
}

fn check_length(series: RateSeries) -> Result<RateSeries, NoiseInputError> {
    match series.axes[0].len() {
        samples if samples < MIN_SAMPLES => Err(NoiseInputError::TooShort { samples }),
        _ => Ok(series),
    }
}

/// Reads CSV text sampled at `rate_hz`.
pub fn read_csv(reader: impl Read, rate_hz: f64) -> Result<RateSeries, NoiseInputError> {
    check_rate(rate_hz)?;
    let mut csv = csv::ReaderBuilder::new().trim(csv::Trim::All).from_reader(reader);
    let header = csv.headers().map_err(|e| bad_line(1, e))?.clone();
    let mut columns = [0usize; 6];
    for (slot, column) in columns.iter_mut().zip(COLUMNS) {
        *slot = header.iter().position(|h| h == column).ok_or(NoiseInputError::MissingColumn { column })?;
    }
    let mut axes: [Vec<f64>; 6] = Default::default();
    for (row, record) in csv.records().enumerate() {
        let record = record.map_err(|e| bad_line(row + 2, e))?;
        for (axis, &column) in axes.iter_mut().zip(&columns) {
            let cell = record.get(column).unwrap_or_default();
            axis.push(cell.parse().map_err(|_| bad_line(row + 2, format!("{cell:?} is not a number")))?);
        }
    }
    check_length(RateSeries { rate_hz, axes })
}

fn bad_line(line: usize, reason: impl ToString) -> NoiseInputError {
    NoiseInputError::BadLine { line, reason: reason.to_string() }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_recording_without_a_gyro_column_is_refused_by_name() {
        let text = "index,ax_g,ay_g,az_g,gx_dps,gy_dps\n0,0,0,1,0,0\n";
        let error = read_csv(text.as_bytes(), 100.0).unwrap_err();
        assert!(matches!(error, NoiseInputError::MissingColumn { column: "gz_dps" }), "{error}");
    }
}
