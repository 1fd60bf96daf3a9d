//! `accelcal noise`: the fitted terms per axis and what they mean for a calibration, as a table.

use std::fmt::Write;

use super::{
    accel_axes, capture_limit_is_lower_bound, capture_limit_s, usual_scale, AxisNoise, NoiseReport,
    CAPTURE_SECONDS_SHOWN, UG_PER_G,
};

/// Seconds of deg/s per deg/h.
const SECONDS_PER_HOUR: f64 = 3600.0;

/// The report as text.
pub fn render(report: &NoiseReport) -> String {
    let mut out = String::new();
    let minutes = report.samples as f64 / report.rate_hz / 60.0;
    let rate = crate::shown::hz(report.rate_hz);
    let _ = writeln!(out, "{} samples at {rate} Hz ({minutes:.1} min) per axis", report.samples);
    if let Some(serial) = &report.board {
        let _ = writeln!(out, "recorded on board {serial}");
    }
    let _ = writeln!(
        out,
        "{:<8} {:>16} {:>16} {:>10} {:>18}",
        "axis", "white noise", "bias instab.", "at tau", "random walk"
    );
    for axis in &report.axes {
        let _ = writeln!(out, "{}", axis_line(axis));
    }
    let _ = writeln!(
        out,
        "(accelerometer in ug, ug/sqrt(Hz), ug/s/sqrt(Hz); gyro in deg/s, deg/s/sqrt(Hz), deg/s/s/sqrt(Hz))\n\
         (white noise one-sided, as datasheets give it; the Allan deviation at 1 s and Kalibr's density are it / sqrt(2))"
    );
    if report.axes.iter().any(|a| a.terms.is_some() && !a.bias_instability_resolved()) {
        out.push_str("(bias instability not resolved: the deviation had not levelled off by the longest averaging time; record longer)\n");
    }
    if report.axes.iter().any(|a| a.terms.is_some() && !a.random_walk_resolved()) {
        out.push_str("(random walk not resolved: the deviation had not begun to rise; < is the largest its longest averaging time allows; record for hours)\n");
    }
    write_gyro_per_hour(&mut out, report);
    write_calibration(&mut out, report);
    out
}

fn axis_line(axis: &AxisNoise) -> String {
    let Some(t) = axis.terms else {
        return format!("{:<8} too short for any averaging time", axis.name);
    };
    let s = usual_scale(axis);
    // NOTE: an unresolved B is what white noise and a short record leave in the fit, not the sensor's.
    let bias = match axis.bias_instability_resolved() {
        true => format!("{:>16.4e} {:>9.1}s", t.bias_instability * s, t.bias_instability_tau_s),
        false => format!("{:>16} {:>10}", "not resolved", "-"),
    };
    let walk = match (axis.random_walk_resolved(), axis.random_walk_bound()) {
        (false, Some(bound)) => format!("< {:.4e}", bound * s),
        _ => format!("{:.4e}", t.random_walk * s),
    };
    format!("{:<8} {:>16.4e} {bias} {walk:>18}", axis.name, t.white_noise_density() * s)
}

fn write_gyro_per_hour(out: &mut String, report: &NoiseReport) {
    for axis in report.axes.iter().filter(|a| !a.is_accel()) {
        if let Some(t) = axis.terms {
            let arw = t.white_noise_n * SECONDS_PER_HOUR.sqrt();
            let bias = match axis.bias_instability_resolved() {
                true => format!("{:.2} deg/h", t.bias_instability * SECONDS_PER_HOUR),
                false => "not resolved".to_owned(),
            };
            let _ = writeln!(out, "{}: angle random walk {arw:.3} deg/sqrt(h), bias instability {bias}", axis.name);
        }
    }
}

fn write_calibration(out: &mut String, report: &NoiseReport) {
    match capture_limit_s(report) {
        Some(limit) if capture_limit_is_lower_bound(report) => {
            let _ = writeln!(out, "the accelerometer's deviation still falls at {limit:.0} s, the longest averaging time this recording resolves: captures help at least that long");
        }
        Some(limit) => {
            let _ = writeln!(out, "captures longer than {limit:.0} s per position stop helping (accelerometer)");
        }
        None => {}
    }
    let longest_s = accel_axes(report).filter_map(|a| a.curve.last().map(|p| p.tau_s)).reduce(f64::max);
    for seconds in CAPTURE_SECONDS_SHOWN {
        // NOTE: past the longest averaging time the recording reaches (a tenth of it:
        // `allan::averaging_factors`), its noise terms say nothing of what a longer mean does (a drift
        // can set in unseen).
        if let Some(longest) = longest_s.filter(|&longest| seconds > longest) {
            let _ = writeln!(
                out,
                "a {seconds:>3.0} s position: beyond the {longest:.1} s this recording resolves (record at least {:.0} s to know)",
                10.0 * seconds
            );
            continue;
        }
        let errors: Vec<String> = accel_axes(report)
            .map(|a| a.terms.map_or("-".to_owned(), |t| format!("{:.1}", t.adev(seconds) * UG_PER_G)))
            .collect();
        let _ = writeln!(out, "a {seconds:>3.0} s position: mean known to {} ug (1 sigma, x y z)", errors.join(" / "));
    }
}
