//! The page's pieces that every section draws with: a figure with its legend, and the line said
//! where a section's data is absent.

use std::fmt::Write;

use crate::report::figure::{Figure, SeriesStyle};
use crate::report::plot::{self, PlotError};
use crate::shown::escape;

/// Said where a section's data is not in the session.
pub const ABSENT: &str = "not part of this session";

/// A figure as inline SVG with its legend.
pub(in crate::report) fn figure(out: &mut String, figure: &Figure) -> Result<(), PlotError> {
    let _ = write!(out, "<figure id=\"{}\">{}<figcaption>{}", figure.id, plot::svg(figure)?, escape(&figure.title));
    for series in &figure.series {
        let _ = write!(
            out,
            "<span class=\"key\"><span class=\"swatch {}\" style=\"background:{}\"></span>{}</span>",
            style_class(series.style),
            plot::colour(series.role),
            escape(&series.name)
        );
    }
    out.push_str("</figcaption></figure>");
    Ok(())
}

/// The legend swatch's shape: a dot for markers, a bar for a line, a pale square for a band.
fn style_class(style: SeriesStyle) -> &'static str {
    match style {
        SeriesStyle::Points => "dot",
        SeriesStyle::Line => "bar",
        SeriesStyle::Band => "band",
    }
}

/// The line said where a section's data is missing.
pub(in crate::report) fn absent(what: &str) -> String {
    format!("<p class=\"absent\">{what}</p>")
}
