//! A board's own stream, as the sketch on it prints it: the dialect and columns found from the
//! lines ([`dialect`]), the units ([`units`]) and the rate ([`timing`]), every line that is not a
//! sample counted with its reason, the still periods found and averaged ([`segment`]), and what the
//! stream costs the calibration ([`cost`]). A saved log (`accelcal fit LOG`, `noise LOG`) and a
//! port that talks on its own go through the same reader. A live stream session's status once a
//! second and when it is done ([`status`]), and what its session keeps of the log ([`kept`]).

pub mod arrival;
mod columns;
mod conventions;
pub mod cost;
pub mod dialect;
mod dropped;
pub mod guide;
mod heard;
pub mod kept;
mod line;
mod log;
pub mod plausible;
mod refusal;
pub mod segment;
pub mod status;
mod still;
pub mod timing;
pub mod turns;
pub mod units;

pub use columns::Columns;
pub use conventions::Dialect;
pub use dialect::Layout;
pub use dropped::{DropReason, Dropped};
pub use heard::read_heard;
pub use log::{
    checked_text, split_lines, text_of, LineReader, StreamLog, StreamOptions, StreamSample, ARRIVAL_RATE_TAG,
};
pub use refusal::text_without_samples;
pub use segment::{segment, Segment, Stillness};
pub use still::{SegmentLines, StillPeriods};
pub use units::{AccelUnit, GyroUnit, UnitWord};

/// Why a stream cannot be read.
#[derive(Debug, thiserror::Error)]
pub enum StreamError {
    #[error("cannot read {path}: {source}")]
    Io { path: String, source: std::io::Error },
    #[error("none of the {lines} lines holds a sample: {why}")]
    NoData { lines: usize, why: String },
    #[error(
        "the lines hold {count} values ({names}) and which are the accelerometer's is unclear: \
         give them a header such as millis,ax,ay,az,gx,gy,gz"
    )]
    UnclearColumns { count: usize, names: String },
    #[error(
        "the accelerometer's values have a median size of {median_norm:.4}, which is 1 g in none of g, mg, m/s2 \
         or the counts of a range: give --input-unit (g, mg, m/s2, counts-2g, counts-4g, counts-8g, counts-16g); \
         a board at rest reads 1 g, so values the size of no unit's g may be no accelerometer's (a log with no sensor)"
    )]
    UnclearUnit { median_norm: f64 },
    #[error(
        "with --input-unit {} the accelerometer's values have a median size of {median_norm:.4}, that is {:.3} g, \
         where a board at rest reads 1 g: they are {} ({} a g), not {}; give --input-unit {}, or leave it out (the \
         size of gravity names the unit)",
        given.name(), median_norm / given.per_g(), likely.name(), likely.per_g(), given.name(), likely.name()
    )]
    OtherAccelUnit { given: AccelUnit, likely: AccelUnit, median_norm: f64 },
    #[error(
        "{beyond} of the {read} samples hold a value beyond what the sensor can read in {units}: the values are not \
         in that unit; give {flag} as the sketch prints them"
    )]
    BeyondReach { beyond: usize, read: usize, units: String, flag: &'static str },
    #[error("--rate {given_hz} differs from the {shown_hz:.3} Hz the stream's timestamps show; leave --rate out")]
    RateDiffers { given_hz: f64, shown_hz: f64 },
    #[error("only {samples} samples were read: a calibration needs a few seconds at each of 9 or more positions")]
    TooFewSamples { samples: usize },
}
