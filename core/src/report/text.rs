//! The reports as text for a person.

use std::fmt::Write;

use super::{shown, Board, CalibrateReport, Comparison, FitReport, SessionReport, NOT_RECORDED};
use crate::fit::{axis_angles_deg, Evaluation, Fit, Model};

/// The fit: parameters with standard errors, then errors before and after in mg, then (for `auto`)
/// the comparison.
pub fn fit_report(report: &FitReport) -> String {
    let mut out = String::new();
    write_fit(&mut out, &report.fit, report.rows, report.g);
    write_rows(&mut out, &report.evaluation, report.g);
    if let Some(comparison) = &report.comparison {
        write_comparison(&mut out, comparison);
    }
    out
}

fn write_fit(out: &mut String, fit: &Fit, rows: usize, g: f64) {
    let used = fit.lines_used.len();
    let _ = writeln!(out, "model {} ({used} of {rows} rows used), |g| = {g}", fit.model.name());
    let _ = writeln!(out, "a = M (m - o); cost {:.3e}, {} iterations", fit.cost, fit.iterations);
    for parameter in &fit.parameters {
        let error = parameter.std_error.map_or("(no redundancy)".to_owned(), |e| format!("+- {e:.2e}"));
        let _ = writeln!(out, "  {:<4} {:>16} {error}", parameter.name, number(parameter.value));
    }
    if let Some(test) = &fit.noise_test {
        let _ = writeln!(out, "{}", test.verdict());
    }
    for warning in &fit.warnings {
        let _ = writeln!(out, "warning: {warning}");
    }
    if let Some(selection) = &fit.selection {
        let _ = writeln!(out, "auto: {}", selection.reason);
    }
    write_meaning(out, fit);
}

/// What the uncertainty means at a fresh orientation, and the angles between the sensor's axes.
fn write_meaning(out: &mut String, fit: &Fit) {
    match &fit.prediction {
        Some(p) if p.misfit_mg.is_some_and(|m| m > 0.0) => {
            let _ = writeln!(
                out,
                "at a fresh orientation expect | |a| - g | of {:.4} mg (RMS): the parameters' uncertainty predicts \
                 {:.4} mg, and the rows left out one at a time show {:.4} mg of misfit beyond it and their noise; \
                 a tilt error of {:.4} degrees (RMS) from the parameters",
                p.norm_error_mg,
                p.from_parameters_mg(),
                p.misfit_mg.unwrap_or(0.0),
                p.tilt_error_deg
            );
        }
        Some(p) => {
            let _ = writeln!(
                out,
                "at a fresh orientation the parameters' uncertainty predicts | |a| - g | of {:.4} mg and a tilt \
                 error of {:.4} degrees (RMS){}",
                p.norm_error_mg,
                p.tilt_error_deg,
                if p.misfit_mg.is_some() { "; the rows left out one at a time show no misfit beyond it" } else { "" }
            );
        }
        None => {}
    }
    if let Some([xy, xz, yz]) = axis_angles_deg(&fit.matrix).filter(|_| fit.model != Model::Diag6) {
        let _ = writeln!(out, "angles between the sensor's axes: x-y {xy:.3}, x-z {xz:.3}, y-z {yz:.3} degrees");
    }
}

fn write_rows(out: &mut String, evaluation: &Evaluation, g: f64) {
    let mg = |value: f64| shown(value / g * 1000.0, 2);
    let angles = evaluation.rows.iter().any(|r| r.inclination_error_deg.is_some());
    if evaluation.before_nominal {
        out.push_str("(the file is not in g: \"before\" is its readings centred and put on a nominal scale of g)\n");
    }
    let _ = write!(out, "line  set    ||a|-g| mg before   after   |a-ref| mg before   after");
    let _ = writeln!(out, "{}", if angles { "  incl err deg  tf err deg" } else { "" });
    for row in &evaluation.rows {
        let set = if row.training { "train" } else { "test" };
        let _ = write!(
            out,
            "{:>4}  {set:<5} {:>17.2} {:>7.2} {} {}",
            row.line,
            mg(row.norm_error_before),
            mg(row.norm_error_after),
            cell(row.reference_error_before.map(mg), 17, 2),
            cell(row.reference_error_after.map(mg), 7, 2)
        );
        if angles {
            let _ = write!(out, " {} {}", cell(row.inclination_error_deg, 13, 3), cell(row.toolface_error_deg, 11, 3));
        }
        out.push('\n');
    }
    write_worst(out, evaluation, g);
}

fn write_worst(out: &mut String, evaluation: &Evaluation, g: f64) {
    let mg = |value: f64| shown(value / g * 1000.0, 2);
    let (before, after) = evaluation.worst_norm_error();
    let _ = writeln!(out, "worst ||a|-g|: {:.2} mg before, {:.2} mg after", mg(before), mg(after));
    if let Some((before, after)) = evaluation.worst_reference_error() {
        let _ = writeln!(out, "worst |a-ref|: {:.2} mg before, {:.2} mg after", mg(before), mg(after));
    }
}

fn write_comparison(out: &mut String, comparison: &Comparison) {
    out.push_str("model comparison (same rows):\n  model             cost        ||a|-g| rms mg train  test\n");
    for m in &comparison.models {
        match &m.refused {
            Some(reason) => {
                let _ = writeln!(out, "  {:<17} not supported: {reason}", m.model);
            }
            None => {
                let cost = m.cost.map_or("-".to_owned(), |c| format!("{c:.3e}"));
                let (train, test) = (cell(m.training_rms_mg, 1, 3), cell(m.test_rms_mg, 1, 3));
                let _ = writeln!(out, "  {:<17} {cost:<11} {train:>20} {test:>6}", m.model);
            }
        }
    }
    if let Some(angle) = comparison.misalignment_deg {
        let _ = writeln!(out, "placement misalignment (12- vs 9-parameter fit): {angle:.2} degrees");
    }
}

/// The result of a calibration: the verification line.
pub fn calibrate_report(report: &CalibrateReport) -> String {
    let v = &report.verification;
    let board = report.board_seconds.map_or(String::new(), |s| {
        format!("the board was kept {s:.1} s from the first capture to the end of the verification\n")
    });
    let orientations = if v.positions == 1 { "orientation" } else { "orientations" };
    // NOTE: an RMS within its noise floor says only that the error is below it, not that it is zero.
    let without = match v.after_rms_without_noise_mg {
        e if e > 0.0 => format!("error without it {e:.3} mg"),
        _ => "the error is within that noise".to_owned(),
    };
    let accel = format!(
        "verified at {} fresh {orientations}: | |a| - 1 g | rms {:.2} mg before, {:.3} mg after (worst {:.3} mg); \
         the captures' own noise {:.3} mg, {without}\n{board}",
        v.positions, v.before_rms_mg, v.after_rms_mg, v.after_max_mg, v.noise_floor_mg
    );
    let verdict = report.target.as_ref().map_or(String::new(), |t| format!("{}\n", t.line));
    accel + &super::gyro::text(&report.calibration.gyro, report.gyro_check.as_ref()) + &verdict
}

/// A number right-aligned in `width` with `digits` decimals, or `-`.
fn cell(value: Option<f64>, width: usize, digits: usize) -> String {
    value.map_or(format!("{:>width$}", "-"), |v| format!("{:>width$.digits$}", shown(v, digits)))
}

/// A parameter value in plain notation where that stays readable, else in scientific notation.
fn number(value: f64) -> String {
    if value == 0.0 || (1e-3..1e5).contains(&value.abs()) {
        format!("{value:+.8}")
    } else {
        format!("{value:+.7e}")
    }
}

/// The session report for a terminal: verdict, board, fit, positions, model comparison.
pub fn session_report(report: &SessionReport) -> String {
    let mut out = format!("{}\n", report.verdict.line);
    write_board(&mut out, &report.board);
    write_session_fit(&mut out, report);
    if let Some(comparison) = &report.comparison {
        write_comparison(&mut out, comparison);
    }
    write_extras(&mut out, report);
    out
}

/// The fit's parameters, and each position's residual before and after.
fn write_session_fit(out: &mut String, report: &SessionReport) {
    if let Some(uploaded) = &report.uploaded {
        let _ = writeln!(out, "uploaded to the board: {}", uploaded.line);
    }
    let fit = &report.fit;
    let _ = writeln!(out, "model {}: cost {:.3e}, | |a| - 1 g | rms {:.3} mg", fit.model, fit.cost, fit.rms_mg);
    for p in &fit.parameters {
        let error = p.std_error.map_or("(no redundancy)".to_owned(), |e| format!("+- {e:.2e}"));
        let _ = writeln!(out, "  {:<5} {:>16} {error}", p.name, number(p.value));
    }
    for p in &report.positions {
        let (before, after) = (p.residual_before_mg, p.residual_after_mg);
        let _ = writeln!(out, "  {:<8} |v| - 1 g: {before:>9.2} mg raw {after:>8.3} mg calibrated", p.name);
    }
}

/// The temperature model, the noise and the gyro's turns, one line each, when given.
fn write_extras(out: &mut String, report: &SessionReport) {
    if let Some(t) = &report.temperature {
        let [x, y, z] = t.offset_change_mg;
        let _ = writeln!(
            out,
            "temperature model around {:.1} degC from {} bins over {:.1}-{:.1} degC: offset changes {x:+.2} {y:+.2} {z:+.2} mg over the span, held-out {:.3} mg",
            t.ref_temp_c, t.bins.len(), t.learned_c[0], t.learned_c[1], t.held_out_mg
        );
    }
    if let Some(a) = &report.allan_deviation {
        let density = |i: usize| a.axes[i].white_noise_density.map_or("-".to_owned(), |d| format!("{d:.1}"));
        let (x, y, z) = (density(0), density(1), density(2));
        let (n, rate) = (a.samples, a.sample_rate_hz);
        let _ = writeln!(
            out,
            "noise: white noise density {x} / {y} / {z} ug/sqrt(Hz) (x y z, one-sided); {n} samples at {rate} Hz"
        );
    }
    if let Some(turns) = &report.gyro_turns {
        let _ = writeln!(out, "{}", super::gyro::turns_line(turns));
    }
}

fn write_board(out: &mut String, board: &Board) {
    let or_absent = |value: &Option<String>| value.clone().unwrap_or_else(|| NOT_RECORDED.to_owned());
    let (serial, firmware) = (or_absent(&board.serial), or_absent(&board.firmware));
    let _ = writeln!(out, "board {serial}, firmware {firmware}, sensor {}", or_absent(&board.sensor_config));
    let range = board.range_g.map_or(NOT_RECORDED.to_owned(), |g| format!("+-{g} g"));
    let _ = writeln!(out, "captured {} UTC, range {range}", or_absent(&board.date_utc));
    if let Some(part) = &board.part {
        let _ = writeln!(out, "sensor part: {part}");
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::session::Verification;
    use shared::{AccelRange, Calibration};

    fn verified(positions: usize, after_rms_mg: f64, noise_floor_mg: f64) -> String {
        let without = (after_rms_mg.powi(2) - noise_floor_mg.powi(2)).max(0.0).sqrt();
        let verification = Verification {
            positions,
            before_rms_mg: 40.0,
            after_rms_mg,
            after_max_mg: after_rms_mg,
            after_rms_without_noise_mg: without,
            on_chip_difference_mg: 0.0,
            on_chip_noise_mg: 1.0,
            noise_floor_mg,
            before_mg: Vec::new(),
            after_mg: Vec::new(),
        };
        let report = CalibrateReport::new(&Calibration::identity(AccelRange::G2), None, None, None, verification, 14);
        calibrate_report(&report).lines().next().unwrap().to_owned()
    }

    #[test]
    fn a_verification_within_its_noise_floor_says_so_instead_of_an_error_of_zero() {
        let within = verified(3, 0.168, 0.190);
        assert!(within.ends_with("the captures' own noise 0.190 mg, the error is within that noise"), "{within}");
        let above = verified(1, 0.3, 0.18);
        assert!(above.starts_with("verified at 1 fresh orientation:"), "{above}");
        assert!(above.ends_with("error without it 0.240 mg"), "{above}");
    }
}
