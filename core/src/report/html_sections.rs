//! The HTML of the report's sections that come from outside the session: the temperature model
//! (`report --thermal`) and the Allan deviation (`report --noise`). Every number carries its JSON
//! pointer, as in [`super::html`].

use std::fmt::Write;

use super::allan::AllanSection;
use super::html::parts::{absent, figure, ABSENT};
use super::html::{cell, span};
use super::plot::PlotError;
use super::session::SessionReport;
use super::temperature::TemperatureSection;

/// The temperature model with its plot, or what to give to have one.
pub fn temperature(out: &mut String, report: &SessionReport) -> Result<(), PlotError> {
    out.push_str("<section><h2>Temperature model</h2>");
    let (Some(t), Some(plot)) = (&report.temperature, &report.figures.temperature) else {
        let _ = write!(out, "{}</section>", absent(&format!("{ABSENT} (give --thermal THERMAL.json)")));
        return Ok(());
    };
    figure(out, plot)?;
    temperature_summary(out, t);
    temperature_table(out, t);
    out.push_str("</section>");
    Ok(())
}

fn temperature_summary(out: &mut String, t: &TemperatureSection) {
    let _ = write!(
        out,
        "<p>around {} degC, learned over {}&ndash;{} degC in {} bins; held-out error {} mg; sensitivity {}</p>",
        span("/temperature/ref_temp_c", t.ref_temp_c, 1),
        span("/temperature/learned_c/0", t.learned_c[0], 1),
        span("/temperature/learned_c/1", t.learned_c[1], 1),
        t.bins.len(),
        span("/temperature/held_out_mg", t.held_out_mg, 3),
        if t.scale_fitted { "fitted" } else { "not observable (one orientation)" }
    );
}

fn temperature_table(out: &mut String, t: &TemperatureSection) {
    out.push_str("<div class=\"table-wrap\"><table><tr><th>axis</th><th>order accel, gyro</th>");
    out.push_str("<th>offset change over the span (mg)</th><th>gyro bias change (deg/s)</th></tr>");
    for k in 0..3 {
        let _ = write!(out, "<tr><td>{}</td><td>{}, {}</td>", ["x", "y", "z"][k], t.accel_order[k], t.gyro_order[k]);
        out.push_str(&cell(&format!("/temperature/offset_change_mg/{k}"), Some(t.offset_change_mg[k]), 2));
        let _ = write!(
            out,
            "{}</tr>",
            cell(&format!("/temperature/gyro_bias_change_dps/{k}"), Some(t.gyro_bias_change_dps[k]), 4)
        );
    }
    out.push_str("</table></div>");
}

/// The Allan deviation with the fitted terms, or what to give to have it.
pub fn allan_deviation(out: &mut String, report: &SessionReport) -> Result<(), PlotError> {
    out.push_str("<section><h2>Allan deviation</h2>");
    let (Some(a), Some(plot)) = (&report.allan_deviation, &report.figures.allan_deviation) else {
        let _ = write!(out, "{}</section>", absent(&format!("{ABSENT} (give --noise NOISE.json or a recording)")));
        return Ok(());
    };
    figure(out, plot)?;
    allan_summary(out, a);
    allan_table(out, a);
    out.push_str("<p class=\"muted\">accelerometer in ug, ug/sqrt(Hz), ug/s/sqrt(Hz); gyro in deg/s, ");
    out.push_str("deg/s/sqrt(Hz), deg/s/s/sqrt(Hz); white noise one-sided, as datasheets give it</p></section>");
    Ok(())
}

fn allan_summary(out: &mut String, a: &AllanSection) {
    let minutes = a.samples as f64 / a.sample_rate_hz / 60.0;
    let _ = write!(
        out,
        "<p>{} samples at {} Hz ({minutes:.1} min)",
        a.samples,
        span("/allan_deviation/sample_rate_hz", a.sample_rate_hz, 0)
    );
    match (a.capture_limit_s, a.capture_limit_is_lower_bound) {
        (Some(limit), true) => {
            let limit = span("/allan_deviation/capture_limit_s", limit, 1);
            let _ = write!(out, "; captures help at least up to {limit} s (the capture limit is only a lower bound: the deviation still fell at the longest averaging time)");
        }
        (Some(limit), false) => {
            let _ = write!(
                out,
                "; captures longer than {} s stop helping",
                span("/allan_deviation/capture_limit_s", limit, 1)
            );
        }
        (None, _) => {}
    }
    out.push_str("</p>");
}

fn allan_table(out: &mut String, a: &AllanSection) {
    out.push_str("<div class=\"table-wrap\"><table><tr><th>axis</th><th>white noise density</th>");
    out.push_str("<th>bias instability</th><th>at tau (s)</th><th>random walk</th></tr>");
    for (i, axis) in a.axes.iter().enumerate() {
        let _ = write!(out, "<tr><td>{}</td>", axis.name);
        let pointer = |key: &str| format!("/allan_deviation/axes/{i}/{key}");
        out.push_str(&cell(&pointer("white_noise_density"), axis.white_noise_density, 4));
        // NOTE: an unresolved B is what white noise and a short record left in the fit: shown, and said.
        let note = if axis.bias_instability_resolved { "</td>" } else { " (not resolved)</td>" };
        out.push_str(&cell(&pointer("bias_instability"), axis.bias_instability, 4).replace("</td>", note));
        out.push_str(&cell(&pointer("bias_instability_tau_s"), axis.bias_instability_tau_s, 1));
        let note = if axis.random_walk_resolved { "</td>" } else { " (not resolved)</td>" };
        let walk = cell(&pointer("random_walk"), axis.random_walk, 4).replace("</td>", note);
        let _ = write!(out, "{walk}</tr>");
    }
    out.push_str("</table></div>");
}

#[cfg(test)]
mod tests {
    use super::*;

    fn section(lower_bound: bool, resolved: bool) -> AllanSection {
        let axis = crate::report::allan::AllanAxis {
            name: "accel_x",
            white_noise_density: Some(390.0),
            bias_instability: Some(126.9),
            bias_instability_tau_s: Some(2.5),
            bias_instability_resolved: resolved,
            random_walk: Some(0.0),
            random_walk_resolved: resolved,
        };
        AllanSection {
            sample_rate_hz: 100.0,
            samples: 3000,
            capture_limit_s: Some(2.5),
            capture_limit_is_lower_bound: lower_bound,
            axes: vec![axis],
        }
    }

    #[test]
    fn a_capture_limit_that_is_only_a_lower_bound_and_an_unresolved_bias_instability_are_said() {
        let (mut bound, mut limit) = (String::new(), String::new());
        allan_summary(&mut bound, &section(true, false));
        allan_summary(&mut limit, &section(false, true));
        assert!(bound.contains("captures help at least up to") && bound.contains("only a lower bound"), "{bound}");
        assert!(limit.contains("stop helping") && !limit.contains("lower bound"), "{limit}");
        let (mut unresolved, mut resolved) = (String::new(), String::new());
        allan_table(&mut unresolved, &section(true, false));
        allan_table(&mut resolved, &section(true, true));
        // The bias instability's and the random walk's.
        assert_eq!(unresolved.matches("(not resolved)").count(), 2, "{unresolved}");
        assert!(!resolved.contains("not resolved"), "{resolved}");
    }
}
