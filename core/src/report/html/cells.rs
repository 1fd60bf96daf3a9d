//! The numbers of the page's tables and lines: each rounded as its column reads best and tagged
//! with where the report's JSON holds it and its full value (the page's numbers are checked against
//! the JSON by those tags).

/// A table cell holding `value` rounded to `digits`, or a dash.
pub(crate) fn cell(pointer: &str, value: Option<f64>, digits: usize) -> String {
    match value {
        Some(value) => format!("<td class=\"num\">{}</td>", span(pointer, value, digits)),
        None => format!("<td class=\"num\" data-json=\"{pointer}\" data-value=\"null\">&ndash;</td>"),
    }
}

/// A cell of a column whose numbers are read together (a matrix, parameter values): always
/// `digits` decimals, so that 0.000254 stands beside 1.001101 rather than as 2.54e-4.
pub(crate) fn fixed_cell(pointer: &str, value: Option<f64>, digits: usize) -> String {
    match value {
        Some(value) => format!("<td class=\"num\">{}</td>", fixed_span(pointer, value, digits)),
        None => cell(pointer, None, digits),
    }
}

/// A cell of standard errors: always scientific, with `significant` digits (an uncertainty's
/// first digits are all it says).
pub(crate) fn scientific_cell(pointer: &str, value: Option<f64>, significant: usize) -> String {
    let decimals = significant.saturating_sub(1);
    match value {
        Some(value) => format!("<td class=\"num\">{}</td>", tagged(pointer, value, &format!("{value:.decimals$e}"))),
        None => cell(pointer, None, 0),
    }
}

/// `value` shown with `digits` decimals, tagged with its JSON pointer and full value.
pub(crate) fn span(pointer: &str, value: f64, digits: usize) -> String {
    tagged(pointer, value, &shown(value, digits))
}

/// A value in a column of vector components: always `digits` decimals (a component near zero next
/// to one near 1 g reads 0.0000, not in scientific notation), never a negative zero.
pub(crate) fn fixed_span(pointer: &str, value: f64, digits: usize) -> String {
    let text = format!("{value:.digits$}");
    let text = if text.trim_start_matches(['-', '0', '.']).is_empty() { format!("{:.digits$}", 0.0) } else { text };
    tagged(pointer, value, &text)
}

/// `text` showing `value`, tagged with where the JSON holds it and its full value.
fn tagged(pointer: &str, value: f64, text: &str) -> String {
    format!("<span data-json=\"{pointer}\" data-value=\"{value:e}\">{text}</span>")
}

/// `digits` decimals, or as many significant digits in scientific notation for small values.
pub fn shown(value: f64, digits: usize) -> String {
    if value != 0.0 && value.abs() < 1e-3 {
        format!("{value:.digits$e}")
    } else {
        format!("{value:.digits$}")
    }
}
