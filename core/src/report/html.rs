//! The session report as one self-contained HTML page: no script, no external file, plots as
//! inline SVG. Every number shown carries `data-json` (its JSON pointer in `report --json`) and
//! `data-value` (the full value), so a test can hold the page to the JSON.

use std::fmt::Write;

use super::figure::Figure;
use super::plot::PlotError;
use super::position::PositionResult;
use super::session::{SessionReport, NOT_RECORDED};
use super::Comparison;
use crate::session::{Board, Verification};
use crate::shown::escape;

mod cells;
use cells::fixed_span;
pub use cells::shown;
pub(super) use cells::{cell, fixed_cell, scientific_cell, span};
pub(super) mod parts;
pub use parts::ABSENT;
use parts::{absent, figure};

const STYLE: &str = include_str!("report.css");

/// The report as an HTML page.
pub fn page(report: &SessionReport) -> Result<String, PlotError> {
    let mut out = head(report);
    board(&mut out, &report.board);
    sphere(&mut out, report)?;
    super::uploaded::html_section(&mut out, report.uploaded.as_ref());
    parameters(&mut out, report);
    if let Some(comparison) = &report.comparison {
        models(&mut out, comparison);
    }
    verification(&mut out, report)?;
    super::html_sections::temperature(&mut out, report)?;
    super::html_sections::allan_deviation(&mut out, report)?;
    gyro_turns(&mut out, report)?;
    out.push_str("</main></body></html>\n");
    Ok(out)
}

/// The page's head, title and verdict line.
fn head(report: &SessionReport) -> String {
    let mut out = String::from("<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">");
    out.push_str("<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">");
    let _ = write!(out, "<title>accelcal report</title><style>{STYLE}</style></head><body><main>");
    out.push_str("<h1>accelcal calibration report</h1>");
    let class = if report.verdict.trusted { "trusted" } else { "untrusted" };
    let _ =
        write!(out, "<p class=\"verdict {class}\" data-json=\"/verdict/line\">{}</p>", escape(&report.verdict.line));
    out
}

fn board(out: &mut String, board: &Board) {
    let missing = || format!("<span class=\"absent\">{NOT_RECORDED}</span>");
    let text = |value: &Option<String>| value.as_deref().map_or_else(missing, escape);
    let range = board.range_g.map_or_else(missing, |g| format!("&plusmn;{g} g"));
    out.push_str("<section><h2>Board</h2><div class=\"table-wrap\"><table>");
    for (name, value) in [
        ("serial number", text(&board.serial)),
        ("firmware", text(&board.firmware)),
        ("sensor", text(&board.part)),
        ("sensor configuration", text(&board.sensor_config)),
        ("accelerometer range", range),
        ("captured (UTC)", text(&board.date_utc)),
    ] {
        let _ = write!(out, "<tr><th>{name}</th><td>{value}</td></tr>");
    }
    out.push_str("</table></div></section>");
}

fn sphere(out: &mut String, report: &SessionReport) -> Result<(), PlotError> {
    out.push_str("<section><h2>Positions on the sphere</h2>");
    out.push_str("<p class=\"muted\">Raw readings lie on an ellipsoid; calibrated ones on the 1 g sphere.</p>");
    out.push_str("<div class=\"plots\">");
    figure(out, &report.figures.sphere_xy)?;
    figure(out, &report.figures.sphere_xz)?;
    out.push_str("</div>");
    pair(out, &report.figures.residuals)?;
    out.push_str("<div class=\"table-wrap\"><table><tr><th>position</th><th>raw x, y, z (g)</th>");
    out.push_str("<th>calibrated x, y, z (g)</th><th>|v| &minus; 1 g raw (mg)</th><th>calibrated (mg)</th></tr>");
    for (i, p) in report.positions.iter().enumerate() {
        position_row(out, i, p);
    }
    out.push_str("</table></div></section>");
    Ok(())
}

fn position_row(out: &mut String, i: usize, p: &PositionResult) {
    let _ = write!(out, "<tr><td>{}</td>", escape(&p.name));
    let vector = |key: &str, v: &[f64; 3]| {
        let cells: Vec<String> = (0..3).map(|k| fixed_span(&format!("/positions/{i}/{key}/{k}"), v[k], 4)).collect();
        format!("<td class=\"num vec\">{}</td>", cells.join(" "))
    };
    out.push_str(&vector("raw_g", &p.raw_g));
    out.push_str(&vector("calibrated_g", &p.calibrated_g));
    let _ = write!(out, "{}", cell(&format!("/positions/{i}/residual_before_mg"), Some(p.residual_before_mg), 2));
    let _ = write!(out, "{}</tr>", cell(&format!("/positions/{i}/residual_after_mg"), Some(p.residual_after_mg), 3));
}

fn parameters(out: &mut String, report: &SessionReport) {
    let fit = &report.fit;
    let _ = write!(out, "<section><h2>Parameters</h2><p>model <b>{}</b>, cost ", fit.model);
    let _ = write!(
        out,
        "{}, | |a| &minus; 1 g | rms {} mg over the positions</p>",
        span("/fit/cost", fit.cost, 3),
        span("/fit/rms_mg", fit.rms_mg, 3)
    );
    out.push_str("<div class=\"table-wrap\"><table><tr><th>parameter</th><th>value</th><th>standard error</th></tr>");
    for p in &fit.parameters {
        // NOTE: the JSON keys parameters by name (`fit::parameters_by_name`); the names need no escaping
        // in a JSON pointer (no `~` or `/`).
        let (name, at) = (p.name, format!("/fit/parameters/{}", p.name));
        let _ = write!(out, "<tr><td>{}</td>{}", escape(name), fixed_cell(&format!("{at}/value"), Some(p.value), 6));
        let _ = write!(out, "{}</tr>", scientific_cell(&format!("{at}/std_error"), p.std_error, 3));
    }
    out.push_str("</table></div>");
    for warning in &fit.warnings {
        let _ = write!(out, "<p>warning: {}</p>", escape(warning));
    }
    out.push_str("</section>");
}

fn models(out: &mut String, comparison: &Comparison) {
    out.push_str("<section><h2>Model comparison</h2><div class=\"table-wrap\"><table>");
    out.push_str("<tr><th>model</th><th>cost</th><th>rms fitted (mg)</th><th>rms held out (mg)</th></tr>");
    for (i, m) in comparison.models.iter().enumerate() {
        let _ = write!(out, "<tr><td>{}</td>", m.model);
        match &m.refused {
            Some(reason) => {
                let _ = write!(out, "<td colspan=\"3\" class=\"muted\">not supported: {}</td></tr>", escape(reason));
            }
            None => {
                let pointer = |key: &str| format!("/comparison/models/{i}/{key}");
                out.push_str(&cell(&pointer("cost"), m.cost, 3));
                out.push_str(&cell(&pointer("training_rms_mg"), m.training_rms_mg, 3));
                let _ = write!(out, "{}</tr>", cell(&pointer("test_rms_mg"), m.test_rms_mg, 3));
            }
        }
    }
    out.push_str("</table></div>");
    if let Some(angle) = comparison.misalignment_deg {
        let _ =
            write!(out, "<p>placement misalignment: {} degrees</p>", span("/comparison/misalignment_deg", angle, 2));
    }
    out.push_str("</section>");
}

fn verification(out: &mut String, report: &SessionReport) -> Result<(), PlotError> {
    out.push_str("<section><h2>Verification at fresh orientations</h2>");
    let Some(v) = &report.verification else {
        let _ = write!(out, "{}</section>", absent(ABSENT));
        return Ok(());
    };
    if let Some(figures) = &report.figures.verification {
        pair(out, figures)?;
    }
    verification_table(out, v);
    out.push_str("</section>");
    Ok(())
}

fn verification_table(out: &mut String, v: &Verification) {
    out.push_str("<div class=\"table-wrap\"><table>");
    let _ = write!(out, "<tr><th>orientations</th><td class=\"num\" data-json=\"/verification/positions\" data-value=\"{0}\">{0}</td></tr>", v.positions);
    for (name, key, value, digits) in [
        ("| |a| &minus; 1 g | rms raw (mg)", "before_rms_mg", v.before_rms_mg, 2),
        ("| |a| &minus; 1 g | rms calibrated (mg)", "after_rms_mg", v.after_rms_mg, 3),
        ("worst calibrated (mg)", "after_max_mg", v.after_max_mg, 3),
        ("noise floor (mg)", "noise_floor_mg", v.noise_floor_mg, 3),
        ("chip vs host (mg)", "on_chip_difference_mg", v.on_chip_difference_mg, 3),
        ("noise of the chip's mean (mg)", "on_chip_noise_mg", v.on_chip_noise_mg, 3),
    ] {
        let _ = write!(out, "<tr><th>{name}</th>{}</tr>", cell(&format!("/verification/{key}"), Some(value), digits));
    }
    out.push_str("</table></div>");
}

fn optional(out: &mut String, title: &str, figure: Option<&Figure>) -> Result<(), PlotError> {
    let _ = write!(out, "<section><h2>{title}</h2>");
    match figure {
        Some(figure) => self::figure(out, figure)?,
        None => out.push_str(&absent(ABSENT)),
    }
    out.push_str("</section>");
    Ok(())
}

/// The gyro's turns: the figure, and per turn its angle three ways and its residual before and
/// after G; "not part of this session" without them.
fn gyro_turns(out: &mut String, report: &SessionReport) -> Result<(), PlotError> {
    let (Some(turns), Some(plot)) = (&report.gyro_turns, &report.figures.gyro_turns) else {
        return optional(out, "Gyro turns", None);
    };
    out.push_str("<section><h2>Gyro turns</h2>");
    figure(out, plot)?;
    out.push_str("<div class=\"table-wrap\"><table><tr><th>turn</th><th>accelerometer (&deg;)</th>");
    out.push_str("<th>raw gyro (&deg;)</th><th>calibrated gyro (&deg;)</th><th>residual raw (&deg;)</th>");
    out.push_str("<th>residual calibrated (&deg;)</th></tr>");
    for (i, t) in turns.iter().enumerate() {
        let _ = write!(out, "<tr><td>{} &rarr; {}</td>", escape(&t.from), escape(&t.to));
        for (key, value) in [
            ("expected_deg", t.expected_deg),
            ("raw_deg", t.raw_deg),
            ("calibrated_deg", t.calibrated_deg),
            ("residual_raw_deg", t.residual_raw_deg),
            ("residual_calibrated_deg", t.residual_calibrated_deg),
        ] {
            let _ = write!(out, "<td class=\"num\">{}</td>", span(&format!("/gyro_turns/{i}/{key}"), value, 3));
        }
        out.push_str("</tr>");
    }
    out.push_str("</table></div></section>");
    Ok(())
}

/// Two figures side by side where the page is wide enough.
fn pair(out: &mut String, figures: &[Figure; 2]) -> Result<(), PlotError> {
    out.push_str("<div class=\"plots\">");
    figure(out, &figures[0])?;
    figure(out, &figures[1])?;
    out.push_str("</div>");
    Ok(())
}

#[cfg(test)]
mod tests;
