//! Numbers as the tool shows them to a person, in text and in the report.

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

#[cfg(test)]
mod tests {
    #[test]
    fn a_value_that_rounds_to_zero_is_shown_without_a_sign() {
        assert_eq!(format!("{:.2}", super::shown(-0.004, 2)), "0.00");
        assert_eq!(format!("{:+.2}", super::shown(-0.004, 2)), "+0.00");
        assert_eq!(format!("{:.2}", super::shown(-0.005, 2)), "-0.01");
        assert_eq!(format!("{:.1}", super::shown(-0.04, 1)), "0.0");
    }
}
