//! `accelcal noise`: the Allan deviation and noise terms of a still recording, or of the longest
//! still period of a sketch's raw stream.

use super::args::NoiseArgs;
use crate::error::Error;
use crate::noise::input::NoiseInputError;
use crate::noise::{self, input, json, text, RateSeries};
use crate::stream::{cost, StillPeriods, StreamLog, StreamOptions};

/// `accelcal noise FILE [--json] [--plot FILE.svg]`.
pub(super) fn noise(args: &NoiseArgs) -> Result<(), Error> {
    let reading = super::terminal::working(format!("reading {}", args.file.display()));
    let series = match input::read_path(&args.file, args.rate) {
        Err(NoiseInputError::MissingColumn { .. } | NoiseInputError::BadLine { .. }) => stream_series(args),
        read => read.map_err(Error::from),
    };
    reading.finish_and_clear();
    let series = series?;
    let samples = series.axes[0].len();
    let analysing = super::terminal::working(format!("Allan deviation of {samples} samples per axis"));
    let report = noise::analyse(&series);
    analysing.finish_and_clear();
    if let Some(path) = &args.plot {
        let document = crate::report::allan::svg_document(&json::NoiseJson::of(&report))?;
        std::fs::write(path, document).map_err(|source| Error::WriteFile { path: path.clone(), source })?;
    }
    if args.json {
        println!("{}", json::render(&report));
    } else {
        print!("{}", text::render(&report));
    }
    Ok(())
}

/// The file as a sketch's stream: its longest still period, said on stderr with what the stream costs.
fn stream_series(args: &NoiseArgs) -> Result<RateSeries, Error> {
    let text =
        crate::stream::read_text(&args.file).map_err(|source| Error::ReadFile { path: args.file.clone(), source })?;
    let options = StreamOptions { rate_hz: args.rate, ..StreamOptions::default() };
    let log = StreamLog::parse(&text, &options).map_err(|source| Error::Stream { path: args.file.clone(), source })?;
    let (longest, series) = noise::stream::longest_still(&log).map_err(NoiseInputError::from)?;
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
