//! The lot as text: one line per parameter, the boards outside the spec, one board's calibrations.

use std::fmt::Write;

use super::{Distribution, LotSummary};
use crate::certificate::Certificate;

/// The lot's summary as lines for the terminal.
pub fn summary(summary: &LotSummary) -> String {
    let boards = if summary.boards == mutant!("lot-text-one-boards", 1, 0) {
        "1 board".to_owned()
    } else {
        format!("{} boards", summary.boards)
    };
    let mut out = format!("{boards} (each by its latest certificate): {}\n", summary.serials.join(", "));
    let _ = writeln!(
        out,
        "{:<6} {:>12} {:>12} {:>12} {:>12} {:>12} {:>7}",
        "", "mean", "std", "min", "max", "max U", "Cpk"
    );
    for distribution in &summary.parameters {
        out.push_str(&parameter_line(distribution));
    }
    let has_spec = summary.parameters.iter().any(|d| d.limits.is_some());
    match (summary.outside.is_empty(), has_spec) {
        (true, true) => out.push_str("no board outside the spec's limits\n"),
        (true, false) => out.push_str("no spec given: --spec SPEC.toml checks every board against its limits\n"),
        (false, _) => {}
    }
    for (serial, names) in &summary.outside {
        let _ = writeln!(out, "board {serial} is outside the limits of {}", names.join(", "));
    }
    out
}

fn parameter_line(d: &Distribution) -> String {
    let std = d.std.map_or("-".to_owned(), |s| format!("{s:.6}"));
    let cpk = d.cpk.map_or("-".to_owned(), |c| format!("{c:.2}"));
    let unit = if d.unit == "1" { String::new() } else { format!(" {}", d.unit) };
    format!(
        "{:<6} {:>12.6} {:>12} {:>12.6} {:>12.6} {:>12.6} {:>7}{unit}\n",
        d.name, d.mean, std, d.min, d.max, d.max_expanded, cpk
    )
}

/// One board's calibrations, oldest first: date, hash and every parameter with its U.
pub fn board(certificates: &[Certificate]) -> String {
    let mut out = String::new();
    for certificate in certificates {
        let serial = certificate.board.serial.as_deref().unwrap_or("");
        let date = certificate.date_utc.as_deref().unwrap_or("(no date)");
        let _ = writeln!(
            out,
            "board {serial}, calibrated {date} UTC ({}), SHA-256 {}",
            certificate.model, certificate.sha256
        );
        for (name, p) in &certificate.parameters {
            let _ = writeln!(out, "  {name:<5} {:>12.6} +- {:.6} {} (k = 2)", p.value, p.expanded, p.unit);
        }
    }
    out
}

/// The lot by station or day: each group's summary, then the drifting stations.
pub fn grouped(grouped: &super::stations::Grouped, by: &str) -> String {
    let mut out = String::new();
    for group in &grouped.groups {
        let _ = writeln!(out, "{by} {}:", group.name);
        out.push_str(&summary(&group.summary));
    }
    for d in &grouped.drifting {
        let unit = if d.unit == "1" { String::new() } else { format!(" {}", d.unit) };
        let _ = writeln!(
            out,
            "station {} drifts from the others: {} mean {:.6}{unit} against {:.6}{unit} ({:+.1} standard errors)",
            d.station, d.parameter, d.mean, d.others_mean, d.standard_errors
        );
    }
    if by == "station" && grouped.drifting.is_empty() {
        out.push_str("no station drifts from the others\n");
    }
    out
}
