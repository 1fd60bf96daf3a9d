//! What a thermal run does with its learning, on any board: the learning shown on a live line and
//! kept after every capture, an interrupted run's bins fitted when they span enough, and the
//! temperature model fitted around the static calibration and made active on the chip.

use std::io::IsTerminal;

use shared::linalg::Vec3;
use shared::protocol::CalibrationSlot;
use shared::Calibration;

use super::error::ThermalError;
use super::{learn, LearnEnd, LearnOptions, LearnStatus, ThermalBins, ThermalBoard};
use crate::calibration as record;
use crate::fit::drift;
use crate::fit::hysteresis::{self, Hysteresis};
use crate::fit::thermal::fit_temperature;
use crate::link::{Client, Connection, LinkError, Port};
use crate::procedure::{Feedback, ProcedureError};
use crate::report::thermal::ThermalFitJson;

/// Capture length while learning and verifying, in seconds.
pub const CAPTURE_S: u8 = 5;

/// How a learning run at `faces` goes: captures of [`CAPTURE_S`], `rest_seconds` between rounds,
/// until the temperature spans `target_span_c` (degC).
pub fn learn_options(faces: Vec<Vec3<f64>>, target_span_c: f64, rest_seconds: f64) -> LearnOptions {
    LearnOptions { faces, capture_seconds: CAPTURE_S, rest_seconds, target_span_c, max_rounds: 10_000 }
}

/// What one learning run gathered.
pub struct Learned {
    /// The bins learned.
    pub bins: ThermalBins,
    /// Why it stopped.
    pub stopped: String,
    /// Whether it ran to its end (not interrupted).
    pub complete: bool,
}

/// Learns into `bins` with the live line on a terminal (none when `quiet`), giving the bins to
/// `keep` after every capture; an interrupted run keeps its bins when they span enough.
pub fn learn_bins(
    connection: &mut Connection,
    board: &mut dyn ThermalBoard,
    options: &LearnOptions,
    quiet: bool,
    mut bins: ThermalBins,
    keep: &mut dyn FnMut(&ThermalBins) -> Result<(), ProcedureError>,
) -> Result<Learned, ThermalError> {
    // NOTE: a live line rewrites itself on a terminal; in a log it would be one endless line.
    let quiet = quiet || !std::io::stderr().is_terminal();
    let mut show = |s: LearnStatus, learned: &ThermalBins| {
        if !quiet {
            let (temp, span, bins, chip) = (s.temp_c, s.span_c, s.bins, s.chip_bins);
            eprint!("\rtemperature {temp:5.1} degC, span {span:4.1} degC, {bins:3} bins (chip bins in the last capture: {chip})");
        }
        keep(learned)
    };
    let learned = learn(connection, board, options, &mut bins, &mut show);
    if !quiet {
        eprintln!();
    }
    match learned {
        Ok(end) => Ok(Learned { bins, stopped: end_text(end).to_owned(), complete: true }),
        Err(error) if bins.check_span().is_ok() => {
            Ok(Learned { bins, stopped: format!("interrupted ({error}); fitted what was learned"), complete: false })
        }
        Err(error) => Err(error.into()),
    }
}

/// Fits the bins of one or two runs and makes the combined calibration active.
pub fn fit_and_activate(
    connection: &mut Connection,
    static_calibration: &Calibration,
    first: &Learned,
    second: Option<&Learned>,
) -> Result<(Calibration, ThermalFitJson), ThermalError> {
    first.bins.check_span()?;
    let mut points = first.bins.points();
    points.extend(second.map(|s| s.bins.points()).unwrap_or_default());
    let fit = fit_temperature(&record::thermal_reference(static_calibration), &points)?;
    let calibration = record::with_temperature(static_calibration, fit.model)?;
    connection.client.set_calibration(calibration)?;
    let temps = points.iter().map(|p| p.temp_c);
    let learned = [temps.clone().fold(f64::MAX, f64::min), temps.fold(f64::MIN, f64::max)];
    let bins = first.bins.len() + second.map_or(0, |s| s.bins.len());
    let stopped =
        second.map_or(first.stopped.clone(), |s| format!("warming: {}; cooling: {}", first.stopped, s.stopped));
    Ok((calibration, ThermalFitJson::new(&fit, &points, bins, learned, stopped)))
}

/// The heating-versus-cooling comparison around the calibration's static matrix and temperature model.
pub fn hysteresis_of(calibration: &Calibration, heating: &ThermalBins, cooling: &ThermalBins) -> Option<Hysteresis> {
    let model = calibration.temperature?;
    let (matrix, _) = record::static_part(calibration);
    hysteresis::compare(&model, &matrix, &heating.points(), &cooling.points())
}

/// Why learning stopped, in words.
fn end_text(end: LearnEnd) -> &'static str {
    match end {
        LearnEnd::SpanReached => "the span was reached",
        LearnEnd::Stalled => "the temperature stalled",
        LearnEnd::RoundLimit => "the round limit was reached",
    }
}

/// The board's active calibration when it carries a learned temperature model, which a new
/// adaptive session keeps (said), else none.
pub fn kept_by_new_session<P: Port>(
    client: &mut Client<P>,
    feedback: &mut dyn Feedback,
) -> Result<Option<Calibration>, LinkError> {
    let learned = drift::learned::kept(client.calibration(CalibrationSlot::Active)?);
    if let Some(model) = learned.and_then(|c| c.temperature) {
        feedback.say(&format!(
            "the board has a learned temperature model (around {:.1} degC): the captures are corrected by it and it \
             stays with the new calibration",
            model.ref_temp_c
        ));
    }
    Ok(learned)
}
