//! The command line's own value checks: what clap refuses as it parses, with the limits in words.

use shared::protocol::{SensorConfig, MAX_CAPTURE_SECONDS, MIN_CAPTURE_SECONDS};

use crate::limits::{BAUD_RANGE, MAX_PLACEMENT_DEG, MAX_THERMAL_SPAN_C, MIN_THERMAL_SPAN_C};
use crate::sim::Pull;

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

/// A baud rate within [`BAUD_RANGE`]; the cause when not.
pub(super) fn baud(text: &str) -> Result<u32, String> {
    let baud: u32 =
        text.parse().map_err(|_| format!("{text:?} is not a baud rate: give a whole number such as 115200"))?;
    if BAUD_RANGE.contains(&baud) {
        Ok(baud)
    } else {
        Err(format!(
            "{baud} Bd is not in {}-{} Bd: below it no sketch prints a sensor, above it no USB UART bridge goes; \
             give the number in the sketch's Serial.begin",
            BAUD_RANGE.start(),
            BAUD_RANGE.end()
        ))
    }
}

/// A target within 0.05-10 mg.
pub(super) fn target_mg(text: &str) -> Result<f64, String> {
    let mg: f64 = text.parse().map_err(|_| format!("{text:?} is not a number of mg"))?;
    if (0.05..=10.0).contains(&mg) {
        Ok(mg)
    } else {
        Err(format!("{mg} mg is not in 0.05-10 mg (below 0.05 mg the sensor's drift, not its noise, sets the error)"))
    }
}

/// A turn-on bias within 0-50 mg.
pub(super) fn turn_on_bias_mg(text: &str) -> Result<f64, String> {
    let mg: f64 = text.parse().map_err(|_| format!("{text:?} is not a number of mg"))?;
    match (0.0..=50.0).contains(&mg) {
        true => Ok(mg),
        false => Err(format!("{mg} mg is not in 0-50 mg (a part's offset tolerance is +-50 mg on x and y)")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_baud_rate_is_taken_within_what_bridges_go_and_a_nonsense_one_refused_with_its_cause() {
        assert_eq!(baud("38400"), Ok(38_400));
        assert_eq!(baud("300"), Ok(300));
        let zero = baud("0").unwrap_err();
        assert!(zero.contains("0 Bd is not in 300-6000000 Bd") && zero.contains("Serial.begin"), "{zero}");
        assert!(baud("9000000").unwrap_err().contains("no USB UART bridge"));
        assert!(baud("fast").unwrap_err().contains("\"fast\" is not a baud rate"));
    }
}
