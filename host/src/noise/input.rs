//! Reading a still recording for the noise analysis: a `.npy` recording as `accelcal record`
//! writes it (told by its magic), or CSV as `accelcal stream` writes it (columns
//! `ax_g,ay_g,az_g,gx_dps,gy_dps,gz_dps`, others ignored) at the rate of its own `time_s` column
//! when it has one, else at the rate the caller names (a recording names its own).

use std::io::Read;
use std::path::Path;

use shared::protocol::Sample;

use super::RateSeries;
use crate::limits::NOISE_MIN_SAMPLES;
use crate::recording::{self, read::is_npy, RecordingError, SAMPLE_COLUMNS, STREAM_COLUMNS};
// NOTE: the core's, named where it lives: the host's `stream` runs a session with the top error,
// which wraps this module's.
use accelcal_core::stream::timing::agrees;

/// The six columns the analysis needs, in [`super::AXES`] order: a recording's sample columns
/// without the temperature.
pub const COLUMNS: [&str; 6] = {
    let c = SAMPLE_COLUMNS;
    [c[0], c[1], c[2], c[3], c[4], c[5]]
};

/// Why a recording cannot be analysed.
#[derive(Debug, thiserror::Error)]
pub enum NoiseInputError {
    #[error("cannot read {path}: {source}")]
    Io { path: String, source: std::io::Error },
    #[error("line 1: the header lacks column {column}; a recording has {}", COLUMNS.join(","))]
    MissingColumn { column: &'static str },
    #[error("line {line}: {reason}")]
    BadLine { line: usize, reason: String },
    #[error("{samples} samples is too few for an Allan deviation: record at least {NOISE_MIN_SAMPLES}")]
    TooShort { samples: usize },
    #[error(transparent)]
    Recording(#[from] RecordingError),
    #[error(transparent)]
    Stream(#[from] super::stream::StillRecordError),
    #[error("--rate must be a positive number of samples per second, got {rate_hz}")]
    BadRate { rate_hz: f64 },
    #[error(
        "--rate {given_hz} differs from the {recorded_hz} Hz the recording was taken at ({shown_by}); leave --rate out"
    )]
    RateDiffers { given_hz: f64, recorded_hz: f64, shown_by: &'static str },
}

/// Sample rate of a CSV file without time stamps when the caller names none, in Hz: the sensor's
/// full rate.
pub const CSV_DEFAULT_RATE_HZ: f64 = 1000.0;

/// Reads a recording file: a `.npy` recording at the rate it names, a CSV file at the rate of its
/// `time_s` column (`rate_hz`, when given, must agree with either), else at `rate_hz` or
/// [`CSV_DEFAULT_RATE_HZ`].
pub fn read_path(path: &Path, rate_hz: Option<f64>) -> Result<RateSeries, NoiseInputError> {
    let io = |source| NoiseInputError::Io { path: path.display().to_string(), source };
    let mut file = std::fs::File::open(path).map_err(io)?;
    let mut magic = [0u8; 6];
    let opened = file.read(&mut magic).map_err(io)?;
    if is_npy(&magic[..opened]) {
        let recording = recording::read_path(path)?;
        let recorded_hz = agreed_rate(rate_hz, f64::from(recording.rate_hz), "as its header names it")?;
        let series = from_samples(&recording.samples, recorded_hz)?;
        return Ok(RateSeries { board: recording.serial, ..series });
    }
    read_csv(std::fs::File::open(path).map_err(io)?, rate_hz)
}

/// The rate a file shows, when `given` (if any) agrees with it.
fn agreed_rate(given: Option<f64>, recorded_hz: f64, shown_by: &'static str) -> Result<f64, NoiseInputError> {
    match given {
        Some(given_hz) if !agrees(given_hz, recorded_hz) => {
            Err(NoiseInputError::RateDiffers { given_hz, recorded_hz, shown_by })
        }
        _ => Ok(recorded_hz),
    }
}

/// The sample rate time stamps show, in Hz: one over the median interval (a lost sample leaves one
/// long interval, which the median passes over); `None` for fewer than two stamps or no progress.
fn rate_of_times(times_s: &[f64]) -> Option<f64> {
    let mut intervals: Vec<f64> = times_s.windows(2).map(|w| w[1] - w[0]).collect();
    intervals.sort_by(f64::total_cmp);
    let median = *intervals.get(intervals.len() / 2)?;
    // NOTE: to the millihertz: the stamps are printed to the microsecond, so finer digits are theirs.
    (median > 0.0).then(|| (1000.0 / median).round() / 1000.0)
}

/// The six axes of recorded samples taken at `rate_hz`.
pub fn from_samples(samples: &[Sample], rate_hz: f64) -> Result<RateSeries, NoiseInputError> {
    check_rate(rate_hz)?;
    let mut axes: [Vec<f64>; 6] = Default::default();
    for sample in samples {
        let values = sample.accel_g.iter().chain(&sample.gyro_dps);
        axes.iter_mut().zip(values).for_each(|(axis, &value)| axis.push(f64::from(value)));
    }
    check_length(RateSeries { rate_hz, axes, board: None })
}

fn check_rate(rate_hz: f64) -> Result<(), NoiseInputError> {
    match rate_hz > 0.0 && rate_hz.is_finite() {
        true => Ok(()),
        false => Err(NoiseInputError::BadRate { rate_hz }),
    }
}

fn check_length(series: RateSeries) -> Result<RateSeries, NoiseInputError> {
    match series.axes[0].len() {
        samples if samples < NOISE_MIN_SAMPLES => Err(NoiseInputError::TooShort { samples }),
        _ => Ok(series),
    }
}

/// Reads CSV text at the rate of its `time_s` column, else at `rate_hz` or [`CSV_DEFAULT_RATE_HZ`];
/// the board is the one its `board` column names.
pub fn read_csv(reader: impl Read, rate_hz: Option<f64>) -> Result<RateSeries, NoiseInputError> {
    rate_hz.map_or(Ok(()), check_rate)?;
    let mut csv = csv::ReaderBuilder::new().trim(csv::Trim::All).from_reader(reader);
    let header = csv.headers().map_err(|e| bad_line(1, e))?.clone();
    let columns = number_columns(&header)?;
    let board_column = header.iter().position(|h| h == "board");
    let (mut axes, mut board): ([Vec<f64>; 7], Option<String>) = Default::default();
    for (row, record) in csv.records().enumerate() {
        let record = record.map_err(|e| bad_line(row + 2, e))?;
        board = board.or_else(|| board_column.and_then(|column| record.get(column)).map(str::to_owned));
        for (axis, &column) in axes.iter_mut().zip(&columns) {
            let cell = record.get(column).unwrap_or_default();
            axis.push(cell.parse().map_err(|_| bad_line(row + 2, format!("{cell:?} is not a number")))?);
        }
    }
    let [ax, ay, az, gx, gy, gz, times_s] = axes;
    let rate_hz = match rate_of_times(&times_s) {
        Some(recorded_hz) => agreed_rate(rate_hz, recorded_hz, "as its time_s column shows")?,
        None => rate_hz.unwrap_or(CSV_DEFAULT_RATE_HZ),
    };
    check_length(RateSeries { rate_hz, axes: [ax, ay, az, gx, gy, gz], board })
}

/// Where the six [`COLUMNS`] are in a CSV header, and `time_s` after them when it has one.
fn number_columns(header: &csv::StringRecord) -> Result<Vec<usize>, NoiseInputError> {
    let at = |name: &str| header.iter().position(|h| h == name);
    let mut columns = Vec::with_capacity(7);
    for column in COLUMNS {
        columns.push(at(column).ok_or(NoiseInputError::MissingColumn { column })?);
    }
    columns.extend(at(STREAM_COLUMNS[1]));
    Ok(columns)
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
        let error = read_csv(text.as_bytes(), Some(100.0)).unwrap_err();
        assert!(matches!(error, NoiseInputError::MissingColumn { column: "gz_dps" }), "{error}");
    }

    const SERIAL: &str = "53494D000000000000000017";

    /// A stream CSV at 50 Hz with one lost sample, as `accelcal stream` writes it.
    fn stream_csv() -> String {
        let mut text = "index,time_s,ax_g,ay_g,az_g,gx_dps,gy_dps,gz_dps,temp_c,board\n".to_owned();
        for i in (0..200u32).filter(|i| *i != 77) {
            text += &format!("{i},{:.6},0.001,0,1,0.1,0,0,25.00,{SERIAL}\n", f64::from(i) * 0.02 + 3.0);
        }
        text
    }

    #[test]
    fn a_stream_csv_is_read_at_the_rate_of_its_own_time_stamps_and_a_different_rate_is_refused() {
        let series = read_csv(stream_csv().as_bytes(), None).unwrap();
        assert!((series.rate_hz - 50.0).abs() < 1e-6, "{} Hz", series.rate_hz);
        assert_eq!(series.axes[2].len(), 199);
        assert_eq!(series.board.as_deref(), Some(SERIAL));
        assert!((read_csv(stream_csv().as_bytes(), Some(50.2)).unwrap().rate_hz - 50.0).abs() < 1e-6);
        let error = read_csv(stream_csv().as_bytes(), Some(1000.0)).unwrap_err().to_string();
        assert!(error.contains("differs from the 50"), "{error}");
    }
}
