//! A board's stream log read as a still recording for `accelcal noise`: its longest still period,
//! said with what the stream's form costs.

use std::path::Path;

use super::{cost, StillPeriods, StreamLog, StreamOptions};
use crate::error::Error;
use crate::noise::input::NoiseInputError;
use crate::noise::RateSeries;

/// The file as a sketch's stream: its longest still period, said on stderr with what the stream costs.
pub fn series(path: &Path, rate_hz: Option<f64>) -> Result<RateSeries, Error> {
    let text = crate::stream::read_text(path).map_err(|source| Error::ReadFile { path: path.to_owned(), source })?;
    let options = StreamOptions { rate_hz, ..StreamOptions::default() };
    let log = StreamLog::parse(&text, &options).map_err(|source| Error::Stream { path: path.to_owned(), source })?;
    let (longest, series) = crate::noise::stream::longest_still(&log).map_err(NoiseInputError::from)?;
    eprintln!(
        "{} stream: the longest still period, lines {}-{}, {} samples at {:.1} Hz",
        log.layout.dialect.name(),
        log.samples[longest.first].line,
        log.samples[longest.last].line,
        longest.samples,
        series.rate_hz
    );
    for cost in cost::costs(&log, &StillPeriods::of(&log).segments) {
        eprintln!("cost: {}", cost.words);
    }
    Ok(series)
}
