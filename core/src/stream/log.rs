//! Reading a stream line by line once its layout is known, and a whole saved log at once: samples
//! in the stream's own units with their line numbers, and every other line counted by reason.

use super::dialect::{Layout, SIDE_RECORDS};
use super::dropped::{DropReason, Dropped};
use super::line::{fields, Fields, Words};
use super::timing::{self, Rate, RateSource};
use super::units::{AccelUnit, GyroUnit};
use super::StreamError;
use crate::limits::{NOT_TEXT_SHARE, STREAM_MIN_SAMPLES};

/// What the command line may settle about a stream.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct StreamOptions {
    /// `--input-unit`: the accelerometer's unit.
    pub accel_unit: Option<AccelUnit>,
    /// `--gyro-unit`: the gyro's unit.
    pub gyro_unit: Option<GyroUnit>,
    /// `--rate`: the sample rate, for a stream without timestamps.
    pub rate_hz: Option<f64>,
}

/// One sample as the stream printed it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StreamSample {
    /// The line it was on (1-based).
    pub line: usize,
    /// Its time, in the time column's unit (a saved log scales it to seconds).
    pub time: Option<f64>,
    /// The accelerometer's values, in the stream's unit.
    pub accel: [f64; 3],
    /// The gyro's values, in the stream's unit, when it has a gyro.
    pub gyro: Option<[f64; 3]>,
}

/// Takes lines of a stream of known layout, one at a time.
#[derive(Debug, Clone)]
pub struct LineReader {
    layout: Layout,
    line: usize,
    /// The lines of a sample printed over several, taken so far.
    pending: Vec<Fields>,
}

impl LineReader {
    /// A reader for lines laid out as `layout`, the next being line 1.
    pub fn new(layout: Layout) -> Self {
        LineReader { layout, line: 0, pending: Vec::new() }
    }

    /// The sample on the next line (or ended by it), or why it has none.
    pub fn read(&mut self, text: &str) -> Result<StreamSample, DropReason> {
        self.line += 1;
        if Some(self.line) == self.layout.header_line {
            return Err(DropReason::Header);
        }
        if text.contains(char::REPLACEMENT_CHARACTER) {
            return Err(DropReason::NotText);
        }
        let parsed = match fields(text) {
            Ok(parsed) => parsed,
            Err(_) if text.trim().is_empty() => return Err(DropReason::Empty),
            Err(Words::Header(_) | Words::Text) => return Err(DropReason::Text),
        };
        if parsed.prefix.as_deref().is_some_and(|p| SIDE_RECORDS.contains(&p)) {
            return Err(DropReason::SideRecord);
        }
        let values = self.gathered(parsed)?;
        let columns = &self.layout.columns;
        let pick = |axes: [usize; 3]| axes.map(|i| values[i]);
        Ok(StreamSample {
            line: self.line,
            time: columns.time.as_ref().map(|(i, _)| values[*i]),
            accel: pick(columns.accel),
            gyro: columns.gyro.map(pick),
        })
    }

    /// The values of a whole sample once `parsed` ends one; a line that begins or carries on a
    /// sample printed over several lines is [`DropReason::Continued`].
    fn gathered(&mut self, parsed: Fields) -> Result<Vec<f64>, DropReason> {
        let record = &self.layout.record;
        if record[self.pending.len()].fits(&parsed) {
            self.pending.push(parsed);
        } else if record[0].fits(&parsed) {
            self.pending = vec![parsed];
        } else {
            self.pending.clear();
            return Err(DropReason::OtherShape);
        }
        if self.pending.len() < record.len() {
            return Err(DropReason::Continued);
        }
        Ok(self.pending.drain(..).flat_map(|f| f.values).collect())
    }

    /// The layout being read.
    pub fn layout(&self) -> &Layout {
        &self.layout
    }
}

/// The text of a saved log: bytes that are not UTF-8 (an ESP32's boot noise) become U+FFFD, so that
/// their lines are dropped as [`DropReason::NotText`] and the rest is read; a file mostly of such
/// bytes (a program, a recording, a stream read at the wrong baud rate) is refused as not text.
pub fn checked_text(bytes: &[u8]) -> std::io::Result<String> {
    let text = text_of(bytes);
    let not_text = text.chars().filter(|&c| c == char::REPLACEMENT_CHARACTER || is_binary_control(c)).count();
    if not_text as f64 > NOT_TEXT_SHARE * text.chars().count() as f64 {
        let words =
            "over a quarter of it is bytes that are not text: a binary file, or a stream saved at the wrong --baud";
        return Err(std::io::Error::new(std::io::ErrorKind::InvalidData, words));
    }
    Ok(text)
}

/// A control character no text log holds (a line's own tab, carriage return and newline aside).
fn is_binary_control(c: char) -> bool {
    c.is_control() && !matches!(c, '\t' | '\r' | '\n')
}

/// The lines of `text`, each ended by a newline, a carriage return and a newline, or a carriage
/// return alone (a sketch that prints `\r` only): what a live stream's arrivals split it into too.
pub fn split_lines(text: &str) -> impl Iterator<Item = &str> {
    let text = text.strip_suffix('\n').unwrap_or(text);
    let text = text.strip_suffix('\r').unwrap_or(text);
    text.split('\n').flat_map(|line| line.strip_suffix('\r').unwrap_or(line).split('\r')).filter(|_| !text.is_empty())
}

/// Bytes from a port or a file as text, those that are not UTF-8 replaced by U+FFFD.
pub fn text_of(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// The line a live session adds at the end of its log: the rate it measured from the lines'
/// arrival, for a stream without timestamps (`StreamLog::parse` reads it back).
pub const ARRIVAL_RATE_TAG: &str = "# accelcal: lines arrived at";

/// The rate a live session's log recorded from the lines' arrival.
pub fn arrival_rate(text: &str) -> Option<f64> {
    let line = split_lines(text).filter(|l| l.starts_with(ARRIVAL_RATE_TAG)).last()?;
    line[ARRIVAL_RATE_TAG.len()..].trim().trim_end_matches("Hz").trim().parse().ok()
}

/// A whole stream, read.
#[derive(Debug, Clone)]
pub struct StreamLog {
    /// Dialect and columns.
    pub layout: Layout,
    /// The samples, times in seconds.
    pub samples: Vec<StreamSample>,
    /// The lines that were not samples.
    pub dropped: Dropped,
    /// The accelerometer's unit.
    pub accel_unit: AccelUnit,
    /// The gyro's unit, and whether it was assumed rather than fixed by the dialect or a flag.
    pub gyro_unit: Option<(GyroUnit, bool)>,
    /// The sample rate, when the stream or the command line gives it.
    pub rate: Option<Rate>,
}

impl StreamLog {
    /// Reads a saved log.
    pub fn parse(text: &str, options: &StreamOptions) -> Result<StreamLog, StreamError> {
        let layout = Layout::detect(split_lines(text))?;
        let mut reader = LineReader::new(layout.clone());
        let mut samples = Vec::new();
        let mut dropped = Dropped::default();
        for line in split_lines(text) {
            match reader.read(line) {
                Ok(sample) => samples.push(sample),
                Err(DropReason::Continued) => {}
                Err(reason) => dropped.add(reason, reader.line),
            }
        }
        let time_unit = time_unit(&layout, &samples);
        samples.iter_mut().for_each(|s| s.time = s.time.zip(time_unit).map(|(t, unit)| t * unit));
        let times: Vec<f64> = samples.iter().filter_map(|s| s.time).collect();
        let arrival = arrival_rate(text).map(|hz| Rate { hz, source: RateSource::ArrivalTimes });
        let rate = timing::rate_of(&times, RateSource::Timestamps).or(arrival);
        StreamLog::new(layout, samples, dropped, rate, options)
    }

    /// A stream read line by line (from a port), its rate from the timestamps or as measured.
    pub fn new(
        layout: Layout,
        samples: Vec<StreamSample>,
        dropped: Dropped,
        rate: Option<Rate>,
        options: &StreamOptions,
    ) -> Result<StreamLog, StreamError> {
        if samples.len() < STREAM_MIN_SAMPLES {
            return Err(StreamError::TooFewSamples { samples: samples.len() });
        }
        let rate = timing::settle(rate, options.rate_hz)
            .map_err(|(given_hz, shown_hz)| StreamError::RateDiffers { given_hz, shown_hz })?;
        let (accel_unit, gyro_unit) = units(&layout, &samples, options)?;
        let read = samples.len();
        let (mut samples, mut dropped) = (samples, dropped);
        let beyond = drop_beyond_range(&mut samples, &mut dropped, accel_unit, gyro_unit.map(|(unit, _)| unit));
        if samples.len() < STREAM_MIN_SAMPLES {
            return Err(beyond_reach(beyond, read, accel_unit, gyro_unit.map(|(unit, _)| unit))
                .unwrap_or(StreamError::TooFewSamples { samples: samples.len() }));
        }
        Ok(StreamLog { layout, samples, dropped, accel_unit, gyro_unit, rate })
    }

    /// The accelerometer's samples in g.
    pub fn accel_g(&self) -> Vec<[f64; 3]> {
        let per_g = self.accel_unit.per_g();
        self.samples.iter().map(|s| s.accel.map(|v| v / per_g)).collect()
    }

    /// The gyro's samples in deg/s, when the stream has a gyro.
    pub fn gyro_dps(&self) -> Option<Vec<[f64; 3]>> {
        let per_dps = self.gyro_unit?.0.per_dps();
        self.samples.iter().map(|s| s.gyro.map(|g| g.map(|v| v / per_dps))).collect()
    }
}

/// The accelerometer's unit (given, checked against gravity's size, or found from it) and the
/// gyro's, with whether it was assumed.
fn units(
    layout: &Layout,
    samples: &[StreamSample],
    options: &StreamOptions,
) -> Result<(AccelUnit, Option<(GyroUnit, bool)>), StreamError> {
    let norm = median_norm(samples);
    let accel_unit = match (options.accel_unit, layout.said.0) {
        (Some(unit), _) => unit.given(layout.dialect, norm)?,
        // NOTE: the unit the line names, unless gravity's size says otherwise (a label's `g` misread).
        (None, Some(said)) if said.fits(norm) => said,
        (None, _) => AccelUnit::infer(layout.dialect, norm)?,
    };
    let gyro_unit = layout.columns.gyro.map(|_| match (options.gyro_unit, layout.said.1) {
        (Some(unit), _) => (unit, false),
        (None, Some(said)) => (said, true),
        (None, None) => GyroUnit::infer(layout.dialect, accel_unit),
    });
    Ok((accel_unit, gyro_unit.map(|(unit, fixed)| (unit, !fixed && options.gyro_unit.is_none()))))
}

/// Moves the samples holding a value the sensor cannot read (a garbled line) to the dropped lines;
/// how many were beyond reach in the accelerometer's unit and in the gyro's.
fn drop_beyond_range(
    samples: &mut Vec<StreamSample>,
    dropped: &mut Dropped,
    accel: AccelUnit,
    gyro: Option<GyroUnit>,
) -> [usize; 2] {
    let beyond = |values: [f64; 3], max: f64| values.iter().any(|v| v.abs() > max);
    let mut counts = [0; 2];
    samples.retain(|sample| {
        let gyro_beyond = sample.gyro.zip(gyro).is_some_and(|(values, unit)| beyond(values, unit.readable_max()));
        let each = [beyond(sample.accel, accel.readable_max()), gyro_beyond];
        counts.iter_mut().zip(each).for_each(|(count, out)| *count += usize::from(out));
        if each.contains(&true) {
            dropped.add(DropReason::BeyondRange, sample.line);
        }
        !each.contains(&true)
    });
    counts
}

/// A stream left too short because most of its `read` samples were beyond the sensor's reach
/// (`beyond`: in the accelerometer's unit, in the gyro's): no garbling does that, a wrong unit does.
fn beyond_reach(beyond: [usize; 2], read: usize, accel: AccelUnit, gyro: Option<GyroUnit>) -> Option<StreamError> {
    let gyro_name = gyro.map_or("", GyroUnit::name);
    let (count, units, flag) = match beyond.map(|n| 2 * n > read) {
        [true, true] => {
            (beyond[0].max(beyond[1]), format!("{} and {gyro_name}", accel.name()), "--input-unit and --gyro-unit")
        }
        [true, false] => (beyond[0], accel.name().to_owned(), "--input-unit"),
        [false, true] => (beyond[1], gyro_name.to_owned(), "--gyro-unit"),
        [false, false] => return None,
    };
    Some(StreamError::BeyondReach { beyond: count, read, units, flag })
}

/// Seconds per unit of the time column: by its name, else by the rate its steps would give.
fn time_unit(layout: &Layout, samples: &[StreamSample]) -> Option<f64> {
    let (_, name) = layout.columns.time.as_ref()?;
    let times: Vec<f64> = samples.iter().filter_map(|s| s.time).collect();
    timing::unit_by_name(name).or_else(|| timing::unit_by_steps(&times))
}

/// The median |a| over the samples, in the stream's unit: gravity's size when the board mostly rests.
fn median_norm(samples: &[StreamSample]) -> f64 {
    let mut norms: Vec<f64> = samples.iter().map(|s| shared::linalg::norm(s.accel)).collect();
    norms.sort_by(f64::total_cmp);
    norms[norms.len() / 2]
}

#[cfg(test)]
mod tests;
