//! Draws a [`Figure`] as inline SVG with plotters' SVG backend. Text stays `<text>` for the
//! browser to set; axes and labels are drawn in [`INK`], which the page's CSS turns into its
//! text colour, so a plot reads on light and dark pages and on paper.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::figure::{Figure, Role, Series, SeriesStyle};

/// Placeholder colour of axes and text; the page's CSS replaces it with `currentColor`.
pub const INK: RGBColor = RGBColor(0, 0, 0);
/// Raw data: orange, a mid-tone readable on white and on near-black (and apart from blue for the
/// colour-blind).
const RAW: RGBColor = RGBColor(0xF5, 0x7C, 0x00);
/// Calibrated data: blue, likewise.
const CALIBRATED: RGBColor = RGBColor(0x3B, 0x82, 0xF6);
/// References: mid grey.
const REFERENCE: RGBColor = RGBColor(0x8A, 0x8A, 0x8A);
/// The three sensor axes: vermilion, bluish green and sky blue of Okabe and Ito's palette, told
/// apart with any colour vision and mid-toned for light and dark pages.
const AXES: [RGBColor; 3] = [RGBColor(0xD5, 0x5E, 0x00), RGBColor(0x00, 0x9E, 0x73), RGBColor(0x56, 0xB4, 0xE9)];

/// The colour of a series.
fn colour_of(role: Role) -> RGBColor {
    match role {
        Role::Raw => RAW,
        Role::Calibrated => CALIBRATED,
        Role::Reference => REFERENCE,
        Role::AxisX => AXES[0],
        Role::AxisY => AXES[1],
        Role::AxisZ => AXES[2],
    }
}

/// The colour of a series as CSS, for the page's legend.
pub fn colour(role: Role) -> String {
    let RGBColor(r, g, b) = colour_of(role);
    format!("#{r:02X}{g:02X}{b:02X}")
}

/// Drawing size in SVG user units; the page scales it to the column width.
pub(super) const SIZE: (u32, u32) = (480, 340);
/// Square drawing for figures with equal axes.
const SQUARE: (u32, u32) = (400, 400);

/// Why a figure could not be drawn (a plotters error, as text).
#[derive(Debug, thiserror::Error)]
#[error("cannot draw the {figure} plot: {reason}")]
pub struct PlotError {
    figure: &'static str,
    reason: String,
}

impl PlotError {
    /// Why the figure `figure` could not be drawn.
    pub(super) fn new(figure: &'static str, reason: String) -> Self {
        PlotError { figure, reason }
    }
}

/// The figure as an `<svg>` element.
pub fn svg(figure: &Figure) -> Result<String, PlotError> {
    let mut out = String::new();
    let size = if figure.equal_axes { SQUARE } else { SIZE };
    draw(figure, SVGBackend::with_string(&mut out, size).into_drawing_area())
        .map_err(|reason| PlotError { figure: figure.id, reason })?;
    Ok(out)
}

fn draw(figure: &Figure, area: DrawingArea<SVGBackend, Shift>) -> Result<(), String> {
    // NOTE: a log plot is drawn on linear axes in log10 of the values, its ticks labelled with
    // the values themselves: one chart type for every figure.
    let drawn = if figure.log_axes { in_log10(figure) } else { figure.clone() };
    let figure = &drawn;
    let (x, y) = ranges(figure);
    let (x_ticks, y_ticks) = match (figure.log_axes, figure.index_x) {
        (true, _) => (Ticks::Log, Ticks::Log),
        (false, true) => (Ticks::Whole, Ticks::Linear),
        (false, false) => (Ticks::Linear, Ticks::Linear),
    };
    let (x_label, y_label) = (tick_label(x_ticks, x.end - x.start), tick_label(y_ticks, y.end - y.start));
    let mut chart = ChartBuilder::on(&area)
        .margin(12)
        .x_label_area_size(52)
        .y_label_area_size(72)
        .build_cartesian_2d(x, y)
        .map_err(|e| e.to_string())?;
    chart
        .configure_mesh()
        .disable_mesh()
        .axis_style(INK)
        .label_style(("sans-serif", 20).into_font().color(&INK))
        .axis_desc_style(("sans-serif", 20).into_font().color(&INK))
        .x_label_formatter(&x_label)
        .y_label_formatter(&y_label)
        .x_desc(figure.x_label.as_str())
        .y_desc(figure.y_label.as_str())
        .draw()
        .map_err(|e| e.to_string())?;
    for series in &figure.series {
        draw_series(&mut chart, series, colour_of(series.role))?;
    }
    area.present().map_err(|e| e.to_string())
}

type Chart<'a, 'b> = ChartContext<
    'a,
    SVGBackend<'b>,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;

fn draw_series(chart: &mut Chart, series: &Series, colour: RGBColor) -> Result<(), String> {
    let points = series.points.iter().map(|[x, y]| (*x, *y));
    match series.style {
        SeriesStyle::Line => chart.draw_series(LineSeries::new(points, colour.stroke_width(2))),
        SeriesStyle::Points => chart.draw_series(points.map(|p| Circle::new(p, 4, colour.filled()))),
        SeriesStyle::Band => {
            chart.draw_series(std::iter::once(Polygon::new(points.collect::<Vec<_>>(), colour.mix(0.2))))
        }
    }
    .map(|_| ())
    .map_err(|e| e.to_string())
}

/// The axis ranges holding every point with a margin; with equal axes, one square range.
fn ranges(figure: &Figure) -> (std::ops::Range<f64>, std::ops::Range<f64>) {
    let points = || figure.series.iter().flat_map(|s| s.points.iter());
    let span = |axis: usize| {
        let (low, high) =
            points().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| (l.min(p[axis]), h.max(p[axis])));
        if low.is_finite() {
            (low, high)
        } else {
            (0.0, 1.0)
        }
    };
    let (x, y) = (span(0), span(1));
    if figure.equal_axes {
        let reach = [x.0, x.1, y.0, y.1].iter().fold(0.0f64, |m, v| m.max(v.abs())) * 1.15;
        return (-reach..reach, -reach..reach);
    }
    (padded(x.0, x.1), padded(y.0, y.1))
}

/// How an axis is labelled.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Ticks {
    /// Values drawn in log10, labelled at whole decades.
    Log,
    /// Any value.
    Linear,
    /// A count (position 1, 2, 3): whole numbers only, no "1.5th position".
    Whole,
}

/// The tick labels of an axis spanning `span`: on a log axis the whole decades; on a count's the
/// whole numbers; else [`short`], with a tick within a billionth of the span of zero read as 0 (the
/// ticks' own arithmetic left -2.78e-17 where 0 was meant).
fn tick_label(ticks: Ticks, span: f64) -> Box<dyn Fn(&f64) -> String> {
    match ticks {
        Ticks::Log => Box::new(power_of_ten),
        Ticks::Whole => Box::new(|value: &f64| match (value - value.round()).abs() < 1e-9 {
            true => short(&value.round()),
            false => String::new(),
        }),
        Ticks::Linear => Box::new(move |value: &f64| short(&if value.abs() < span * 1e-9 { 0.0 } else { *value })),
    }
}

/// A tick label: the shortest form that reads back as the tick (2, 0.5, -60), in scientific
/// notation for ticks below 0.001 (residuals of 1e-13 mg would otherwise all read "0").
pub fn short(value: &f64) -> String {
    // NOTE: adding 0.0 turns -0 into 0.
    let value = *value + 0.0;
    if value != 0.0 && value.abs() < 1e-3 {
        let text = format!("{value:.2e}");
        let (mantissa, exponent) = text.split_once('e').unwrap_or((&text, "0"));
        let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
        return format!("{mantissa}e{exponent}");
    }
    format!("{}", (value * 1e6).round() / 1e6 + 0.0)
}

/// A tick label on a log axis drawn in log10: the value itself at whole decades, none between
/// (half-decade labels such as 0.00316 ran into each other).
fn power_of_ten(exponent: &f64) -> String {
    if (exponent - exponent.round()).abs() > 1e-9 {
        return String::new();
    }
    let value = 10f64.powf(exponent.round());
    let rounded = format!("{value:.2e}").parse::<f64>().unwrap_or(value);
    short(&rounded)
}

/// The figure with every point in log10 (points that are not positive are left out).
fn in_log10(figure: &Figure) -> Figure {
    let mut drawn = figure.clone();
    for series in &mut drawn.series {
        series.points.retain(|[x, y]| *x > 0.0 && *y > 0.0);
        series.points.iter_mut().for_each(|p| *p = [p[0].log10(), p[1].log10()]);
    }
    drawn
}

/// A range with a tenth of its width added on each side (half a unit around a single value).
fn padded(low: f64, high: f64) -> std::ops::Range<f64> {
    let pad = if high > low { (high - low) * 0.1 } else { 0.5 };
    (low - pad)..(high + pad)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tick_labels_of_tiny_values_keep_their_digits() {
        assert_eq!(short(&1e-13), "1e-13");
        assert_eq!(short(&-2.5e-13), "-2.5e-13");
        assert_eq!(short(&-0.0), "0");
        assert_eq!(short(&0.5), "0.5");
        assert_eq!(short(&-60.0), "-60");
        // A zero tick off by the ticks' rounding reads 0; a tick of a 1e-13-wide axis keeps its digits.
        assert_eq!(tick_label(Ticks::Linear, 0.4)(&-2.78e-17), "0");
        assert_eq!(tick_label(Ticks::Linear, 4e-13)(&1e-13), "1e-13");
        // A count's axis (positions, turns) is labelled at whole numbers only.
        let (whole, linear) = (tick_label(Ticks::Whole, 3.0), tick_label(Ticks::Linear, 3.0));
        assert_eq!((whole(&1.5), whole(&2.0), linear(&1.5)), (String::new(), "2".to_owned(), "1.5".to_owned()));
        assert_eq!(power_of_ten(&-2.0), "0.01");
        assert_eq!(power_of_ten(&3.0), "1000");
        assert_eq!(power_of_ten(&0.5), "");
    }
}
