//! Values as the tool shows them to a person, in text, in the report and in the certificate: numbers
//! without a -0 sign, dates to the minute in UTC, text made safe inside an HTML page.

/// `value` as shown with `digits` decimals: a value that rounds to zero is shown as zero, never as
/// the `-0.00` a tiny negative number would print.
pub fn shown(value: f64, digits: usize) -> f64 {
    let scale = 10f64.powi(digits as i32);
    if (value * scale).round() == 0.0 {
        0.0
    } else {
        value
    }
}

/// A rate in Hz to the millihertz, without trailing zeros: `100`, `298.123` (a rate from
/// timestamps in ms comes out as 100.00000000000213).
pub fn hz(rate_hz: f64) -> String {
    let text = format!("{rate_hz:.3}");
    text.trim_end_matches('0').trim_end_matches('.').to_owned()
}

/// A rate in Hz to the millihertz as a number, for JSON: the rate [`hz`] shows (100, not
/// 100.00000000000213).
pub fn hz_value(rate_hz: f64) -> f64 {
    (rate_hz * 1e3).round() / 1e3
}

/// Seconds since the Unix epoch as `YYYY-MM-DD HH:MM` UTC (the epoch itself for a time `time`
/// cannot represent).
pub fn utc_minutes(unix_time_s: f64) -> String {
    let at = time::OffsetDateTime::from_unix_timestamp(unix_time_s.max(0.0) as i64)
        .unwrap_or(time::OffsetDateTime::UNIX_EPOCH);
    let (year, month, day) = (at.year(), u8::from(at.month()), at.day());
    format!("{year:04}-{month:02}-{day:02} {:02}:{:02}", at.hour(), at.minute())
}

/// `text` made safe inside an HTML element or a quoted attribute.
pub fn escape(text: &str) -> String {
    text.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

#[cfg(test)]
mod tests {
    #[test]
    fn dates_are_utc_calendar_dates() {
        assert_eq!(super::utc_minutes(0.0), "1970-01-01 00:00");
        assert_eq!(super::utc_minutes(951_782_400.0 + 3_660.0), "2000-02-29 01:01");
        assert_eq!(super::utc_minutes(1_795_000_000.0), "2026-11-18 11:06");
    }

    #[test]
    fn a_rate_is_shown_to_the_millihertz_without_trailing_zeros() {
        assert_eq!(super::hz(100.00000000000213), "100");
        assert_eq!(super::hz(298.12345), "298.123");
        assert_eq!(super::hz(9.5), "9.5");
    }

    #[test]
    fn a_value_that_rounds_to_zero_is_shown_without_a_sign() {
        assert_eq!(format!("{:.2}", super::shown(-0.004, 2)), "0.00");
        assert_eq!(format!("{:+.2}", super::shown(-0.004, 2)), "+0.00");
        assert_eq!(format!("{:.2}", super::shown(-0.005, 2)), "-0.01");
        assert_eq!(format!("{:.1}", super::shown(-0.04, 1)), "0.0");
    }
}
