//! The command line's own value checks: what clap refuses as it parses, with the limits in words.

use shared::protocol::{SensorConfig, MAX_CAPTURE_SECONDS, MIN_CAPTURE_SECONDS};

use crate::limits::{MAX_PLACEMENT_DEG, MAX_THERMAL_SPAN_C, MIN_THERMAL_SPAN_C};
use crate::procedure::Pull;

/// The capture lengths the device accepts, refused when parsed.
pub(super) fn seconds() -> clap::builder::RangedI64ValueParser<u8> {
    clap::value_parser!(u8).range(i64::from(MIN_CAPTURE_SECONDS)..=i64::from(MAX_CAPTURE_SECONDS))
}

/// A placement error in degrees within 0-[`MAX_PLACEMENT_DEG`].
pub(super) fn placement_deg(text: &str) -> Result<f64, String> {
    let deg: f64 = text.parse().map_err(|_| format!("{text:?} is not a number of degrees"))?;
    if (0.0..=MAX_PLACEMENT_DEG).contains(&deg) {
        Ok(deg)
    } else {
        Err(format!("{deg} is not in 0-{MAX_PLACEMENT_DEG} degrees"))
    }
}

/// `K:N`: board K's cable pulled after the fixture's N-th turn (both from 1).
pub(super) fn pull(text: &str) -> Result<Pull, String> {
    let numbers =
        text.split_once(':').and_then(|(k, n)| Some((k.trim().parse::<usize>().ok()?, n.trim().parse().ok()?)));
    match numbers {
        Some((board @ 1.., turn @ 1..)) => Ok(Pull { board: board - 1, turn }),
        _ => Err(format!("{text:?} is not K:N (board K's cable pulled after turn N, both from 1), such as 3:5")),
    }
}

/// A thermal learning target in [`MIN_THERMAL_SPAN_C`]-[`MAX_THERMAL_SPAN_C`] degC.
pub(super) fn target_span_c(text: &str) -> Result<f64, String> {
    let span: f64 = text.parse().map_err(|_| format!("{text:?} is not a number of degC"))?;
    if (MIN_THERMAL_SPAN_C..=MAX_THERMAL_SPAN_C).contains(&span) {
        Ok(span)
    } else {
        Err(format!("{span} is not in {MIN_THERMAL_SPAN_C}-{MAX_THERMAL_SPAN_C} degC (a temperature model needs at least {MIN_THERMAL_SPAN_C})"))
    }
}

/// A stream rate that divides the sensor's sample rate.
pub(super) fn stream_rate(text: &str) -> Result<u16, String> {
    let sample_rate_hz = SensorConfig::default().sample_rate_hz;
    let rate: u16 = text.parse().map_err(|_| format!("{text:?} is not a whole number of samples per second"))?;
    if rate > 0 && sample_rate_hz % rate == 0 {
        Ok(rate)
    } else {
        Err(format!("{rate} does not divide the {sample_rate_hz} Hz sample rate (for example 1, 10, 50 or 100)"))
    }
}

/// Help for a capture length, with the limits the device accepts.
pub(super) fn seconds_help(what: &str) -> String {
    format!("{what} ({MIN_CAPTURE_SECONDS}-{MAX_CAPTURE_SECONDS})")
}

/// Help for a stream rate, with the sample rate it must divide.
pub(super) fn rate_help() -> String {
    format!("Samples per second (must divide the {} Hz sample rate)", SensorConfig::default().sample_rate_hz)
}
