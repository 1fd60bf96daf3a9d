//! `accelcal noise --plot FILE.svg`: log-log Allan deviation per axis with its confidence band and the
//! fitted noise line, one panel for the accelerometer (ug) and one for the gyro (deg/s).

use std::fmt::Write;

use super::json::usual_scale;
use super::{AxisNoise, NoiseReport};

const PANEL_WIDTH: f64 = 560.0;
const PANEL_HEIGHT: f64 = 400.0;
const MARGIN: f64 = 60.0;
const COLOURS: [&str; 3] = ["#d62728", "#2ca02c", "#1f77b4"];

/// Log-log bounds of one panel: decades of tau and of the deviation.
struct Frame {
    left: f64,
    tau_decades: (f64, f64),
    adev_decades: (f64, f64),
}

impl Frame {
    fn point(&self, tau_s: f64, adev: f64) -> (f64, f64) {
        let fx = (tau_s.log10() - self.tau_decades.0) / (self.tau_decades.1 - self.tau_decades.0);
        let fy = (adev.log10() - self.adev_decades.0) / (self.adev_decades.1 - self.adev_decades.0);
        (
            self.left + MARGIN + fx * (PANEL_WIDTH - 1.5 * MARGIN),
            PANEL_HEIGHT - MARGIN - fy * (PANEL_HEIGHT - 1.5 * MARGIN),
        )
    }
}

/// The report as an SVG document.
pub fn render(report: &NoiseReport) -> String {
    let mut svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}\" height=\"{PANEL_HEIGHT}\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n",
        2.0 * PANEL_WIDTH
    );
    for (panel, (accel, title)) in
        [(true, "accelerometer: Allan deviation, ug"), (false, "gyro: Allan deviation, deg/s")].into_iter().enumerate()
    {
        let axes: Vec<&AxisNoise> = report.axes.iter().filter(|a| a.is_accel() == accel).collect();
        if let Some(frame) = frame_for(&axes, panel as f64 * PANEL_WIDTH) {
            draw_panel(&mut svg, &frame, &axes, title);
        }
    }
    svg.push_str("</svg>\n");
    svg
}

/// Decade bounds that hold every point and band of the axes; `None` when they have no points.
fn frame_for(axes: &[&AxisNoise], left: f64) -> Option<Frame> {
    let points = axes.iter().flat_map(|a| a.curve.iter().map(move |p| (p, usual_scale(a))));
    let (mut taus, mut devs) = ((f64::INFINITY, f64::NEG_INFINITY), (f64::INFINITY, f64::NEG_INFINITY));
    for (p, scale) in points.filter(|(p, _)| p.adev > 0.0) {
        taus = (taus.0.min(p.tau_s), taus.1.max(p.tau_s));
        devs = (devs.0.min(p.adev_low * scale), devs.1.max(p.adev_high * scale));
    }
    if !taus.0.is_finite() || !devs.0.is_finite() || devs.0 <= 0.0 {
        return None;
    }
    let decades = |(low, high): (f64, f64)| (low.log10().floor(), high.log10().ceil().max(low.log10().floor() + 1.0));
    Some(Frame { left, tau_decades: decades(taus), adev_decades: decades(devs) })
}

fn draw_panel(svg: &mut String, frame: &Frame, axes: &[&AxisNoise], title: &str) {
    draw_grid(svg, frame);
    let (x, _) = frame.point(10f64.powf(frame.tau_decades.0), 1.0);
    let _ = writeln!(svg, "<text x=\"{x}\" y=\"20\" font-weight=\"bold\">{title}</text>");
    for (k, (axis, colour)) in axes.iter().zip(COLOURS).enumerate() {
        draw_axis(svg, frame, axis, colour);
        let _ = writeln!(
            svg,
            "<text x=\"{}\" y=\"{}\" fill=\"{colour}\">{}</text>",
            x + 10.0,
            60.0 + 16.0 * k as f64,
            axis.name
        );
    }
    let (cx, cy) =
        frame.point(10f64.powf((frame.tau_decades.0 + frame.tau_decades.1) / 2.0), 10f64.powf(frame.adev_decades.0));
    let _ = writeln!(svg, "<text x=\"{cx}\" y=\"{}\" text-anchor=\"middle\">averaging time tau, s (dashed: fitted noise terms; band: 68 % interval)</text>", cy + 40.0);
}

fn draw_grid(svg: &mut String, frame: &Frame) {
    let (t0, t1) = frame.tau_decades;
    let (d0, d1) = frame.adev_decades;
    for t in (t0 as i32)..=(t1 as i32) {
        let (x0, y0) = frame.point(10f64.powi(t), 10f64.powf(d0));
        let (_, y1) = frame.point(10f64.powi(t), 10f64.powf(d1));
        let _ = writeln!(svg, "<line x1=\"{x0}\" y1=\"{y0}\" x2=\"{x0}\" y2=\"{y1}\" stroke=\"#ddd\"/><text x=\"{x0}\" y=\"{}\" text-anchor=\"middle\">1e{t}</text>", y0 + 16.0);
    }
    for d in (d0 as i32)..=(d1 as i32) {
        let (x0, y0) = frame.point(10f64.powf(t0), 10f64.powi(d));
        let (x1, _) = frame.point(10f64.powf(t1), 10f64.powi(d));
        let _ = writeln!(svg, "<line x1=\"{x0}\" y1=\"{y0}\" x2=\"{x1}\" y2=\"{y0}\" stroke=\"#ddd\"/><text x=\"{}\" y=\"{}\" text-anchor=\"end\">1e{d}</text>", x0 - 4.0, y0 + 4.0);
    }
}

fn draw_axis(svg: &mut String, frame: &Frame, axis: &AxisNoise, colour: &str) {
    let scale = usual_scale(axis);
    let at = |tau: f64, dev: f64| {
        let (x, y) = frame.point(tau, dev * scale);
        format!("{x:.1},{y:.1}")
    };
    let upper = axis.curve.iter().map(|p| at(p.tau_s, p.adev_high));
    let lower = axis.curve.iter().rev().map(|p| at(p.tau_s, p.adev_low));
    let band: Vec<String> = upper.chain(lower).collect();
    let _ = writeln!(svg, "<polygon points=\"{}\" fill=\"{colour}\" fill-opacity=\"0.15\"/>", band.join(" "));
    let line: Vec<String> = axis.curve.iter().map(|p| at(p.tau_s, p.adev)).collect();
    let _ = writeln!(svg, "<polyline points=\"{}\" fill=\"none\" stroke=\"{colour}\"/>", line.join(" "));
    if let Some(terms) = axis.terms {
        let fitted: Vec<String> = axis.curve.iter().map(|p| at(p.tau_s, terms.adev(p.tau_s))).collect();
        let _ = writeln!(
            svg,
            "<polyline points=\"{}\" fill=\"none\" stroke=\"{colour}\" stroke-dasharray=\"5,4\"/>",
            fitted.join(" ")
        );
    }
}
