//! The certificate as a printable, self-contained HTML page (A4, no script, no external file).

use std::fmt::Write;

use super::{Certificate, CertifiedValue, Component, Conditions, Interval};
use crate::shown::escape;

const STYLE: &str = "body{font-family:sans-serif;max-width:52em;margin:2em auto;color:#111}\
table{border-collapse:collapse;margin:0.5em 0}td,th{border:1px solid #999;padding:0.2em 0.5em;text-align:right}\
th{background:#eee}td{white-space:nowrap}td.name,th.name{text-align:left;white-space:normal}.hash{font-family:monospace;word-break:break-all}\
@page{size:A4;margin:15mm}@media print{body{margin:0}}";

/// Every budget component, in the page's column order.
const COMPONENTS: [(Component, &str); 5] = [
    (Component::Noise, "noise"),
    (Component::Quantisation, "quantisation"),
    (Component::Temperature, "temperature"),
    (Component::BiasWander, "bias wander"),
    (Component::Placement, "placement"),
];

/// The certificate's page.
pub fn page(certificate: &Certificate) -> String {
    let mut out = format!(
        "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>calibration certificate {}</title>\
         <style>{STYLE}</style></head><body><h1>Calibration certificate</h1>",
        escape(certificate.board.serial.as_deref().unwrap_or("(no serial)"))
    );
    identity(&mut out, certificate);
    parameters(&mut out, certificate);
    predicted(&mut out, certificate);
    verification(&mut out, certificate);
    let _ = writeln!(
        out,
        "<h2>Integrity</h2><p>SHA-256 of the certificate's content (its JSON, keys sorted, without this field): \
         <span class=\"hash\">{}</span>. Check a copy with <code>accelcal certificate verify FILE</code>.</p>\
         </body></html>",
        certificate.sha256
    );
    out
}

/// Board, date, method, model and conditions.
fn identity(out: &mut String, c: &Certificate) {
    let absent = || "not reported by the board".to_owned();
    let conditions = &c.conditions;
    let rows = [
        ("serial number", c.board.serial.clone().unwrap_or_else(absent)),
        ("sensor part", c.board.part.clone().unwrap_or_else(absent)),
        ("firmware", c.board.firmware.clone().unwrap_or_else(absent)),
        ("sensor configuration", c.board.sensor_config.clone().unwrap_or_else(absent)),
        ("date (UTC)", c.date_utc.clone().unwrap_or_else(absent)),
        ("method", c.method.clone()),
        ("model", c.model.clone()),
        ("die temperature", die_temperature(conditions)),
        ("unit of g", format!("{} = the gravity where the board was captured", conditions.g)),
        ("captures", conditions.captures.to_string()),
        ("self-test", c.self_test.as_ref().map_or_else(absent, self_test_summary)),
    ];
    out.push_str("<table>");
    for (name, value) in rows {
        let _ = write!(out, "<tr><th class=\"name\">{name}</th><td class=\"name\">{}</td></tr>", escape(&value));
    }
    out.push_str("</table>");
}

/// The captures' die temperatures, or why there are none.
fn die_temperature(conditions: &Conditions) -> String {
    match (conditions.temp_mean_c, conditions.temp_low_c, conditions.temp_high_c) {
        (Some(mean), Some(low), Some(high)) => format!("{mean:.2} degC mean ({low:.2} to {high:.2} degC)"),
        _ => "not measured (the captures carry no temperature)".to_owned(),
    }
}

/// The self-test the board kept, for a reader: its verdict, date and largest deviation from the
/// factory trim (the JSON holds every axis).
fn self_test_summary(kept: &serde_json::Value) -> String {
    let result = &kept["result"];
    let verdict = match result["passed"].as_bool() {
        Some(true) => "passed",
        Some(false) => "failed",
        None => "no verdict",
    };
    let axes = result["axes"].as_array().map(Vec::as_slice).unwrap_or_default();
    let deviations = axes.iter().filter_map(|axis| axis["deviation_percent"].as_f64());
    let largest = deviations.map(f64::abs).reduce(f64::max);
    let date = kept["date_utc"].as_str().unwrap_or("undated");
    match largest {
        Some(percent) => format!("{verdict} ({date} UTC); largest deviation from the factory trim {percent:.1} %"),
        None => format!("{verdict} ({date} UTC)"),
    }
}

/// The parameters with u, U and the budget's components.
fn parameters(out: &mut String, c: &Certificate) {
    let _ = write!(
        out,
        "<h2>Parameters</h2><p>u: standard uncertainty; U: expanded uncertainty, k = {}. The budget's columns \
         are the standard uncertainty each source contributes.</p><table><tr><th class=\"name\">parameter</th>\
         <th>value</th><th>u</th><th>U</th><th>unit</th>",
        c.coverage_factor
    );
    COMPONENTS.iter().for_each(|(_, name)| {
        let _ = write!(out, "<th>{name}</th>");
    });
    out.push_str("</tr>");
    for (name, p) in &c.parameters {
        parameter_row(out, name, p);
    }
    out.push_str("</table>");
}

fn parameter_row(out: &mut String, name: &str, p: &CertifiedValue) {
    let _ = write!(
        out,
        "<tr><td class=\"name\">{}</td><td>{:.7}</td><td>{:.2e}</td><td>{:.2e}</td><td>{}</td>",
        escape(name),
        p.value,
        p.u,
        p.expanded,
        escape(&p.unit)
    );
    for (component, _) in COMPONENTS {
        match p.budget.get(&component) {
            Some(u) => write!(out, "<td>{u:.1e}</td>"),
            None => write!(out, "<td>-</td>"),
        }
        .unwrap_or_default();
    }
    out.push_str("</tr>");
}

/// The errors predicted at fresh orientations.
fn predicted(out: &mut String, c: &Certificate) {
    let row = |name: &str, unit: &str, i: &Interval| {
        format!("<tr><td class=\"name\">{name}</td><td>{:.4}</td><td>{:.4}</td><td>{unit}</td></tr>", i.u, i.expanded)
    };
    let _ = write!(
        out,
        "<h2>Predicted error at a fresh orientation</h2><table><tr><th class=\"name\">error</th><th>u</th><th>U</th>\
         <th>unit</th></tr>{}{}</table>",
        row("| |a| - g |", "mg", &c.predicted.norm_error_mg),
        row("tilt", "deg", &c.predicted.tilt_error_deg)
    );
}

/// The verification, when one was made.
fn verification(out: &mut String, c: &Certificate) {
    out.push_str("<h2>Verification</h2>");
    let Some(v) = &c.verification else {
        out.push_str("<p>not verified at fresh orientations</p>");
        return;
    };
    let _ = write!(
        out,
        "<p>| |a| - g | at {} fresh orientations: rms {:.3} mg, largest {:.3} mg (noise floor {:.3} mg; \
         {:.2} mg uncalibrated)</p>",
        v.positions, v.after_rms_mg, v.after_max_mg, v.noise_floor_mg, v.before_rms_mg
    );
}
