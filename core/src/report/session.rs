//! The report of a calibration session: the board, the verdict, every position before and after,
//! the fit with its uncertainties and the models it was chosen from, the verification, and the
//! figures drawn from them. Computed once; [`super::html`], [`super::text`] and JSON render it.

use serde::Serialize;
use shared::linalg;

use super::allan::AllanSection;
use super::figure::{self, Figure};
use super::position::{residual_mg, PositionResult};
use super::temperature::TemperatureSection;
use super::uploaded::Uploaded;
use super::{Comparison, FitReport};
use crate::data::Dataset;
use crate::fit::gyro::TurnSummary;
use crate::fit::{parameters_by_name, FitError, FitOptions, Parameter};
use crate::session::{Board, Session, Verification};

/// Shown for what the session does not carry.
pub const NOT_RECORDED: &str = "not recorded";

/// Everything a session's report shows; `accelcal report SESSION --json` prints it.
#[derive(Debug, Clone, Serialize)]
pub struct SessionReport {
    /// The board the session was captured on.
    pub board: Board,
    /// The verdict in one line.
    pub verdict: Verdict,
    /// Every captured position, raw and calibrated.
    pub positions: Vec<PositionResult>,
    /// The record uploaded to the board (the gyro's G included), when the session holds it; the
    /// positions are calibrated by it.
    pub uploaded: Option<Uploaded>,
    /// The host's refit of the captures, with every parameter's standard error, for the comparison.
    pub fit: FitSummary,
    /// Every model on the same positions.
    pub comparison: Option<Comparison>,
    /// The check at fresh orientations, when the session holds one.
    pub verification: Option<Verification>,
    /// The board's temperature model and its bins, when a thermal report is given.
    pub temperature: Option<TemperatureSection>,
    /// The board's noise, when a noise report (or a recording) is given.
    pub allan_deviation: Option<AllanSection>,
    /// The plots, each with the numbers it is drawn from.
    pub figures: Figures,
    /// The gyro's turns between the positions, when the session recorded them.
    pub gyro_turns: Option<Vec<TurnSummary>>,
}

/// The one-line verdict.
#[derive(Debug, Clone, Serialize)]
pub struct Verdict {
    /// Whether the calibration can be trusted to the stated figure.
    pub trusted: bool,
    /// The verdict for a person.
    pub line: String,
}

/// The fit chosen.
#[derive(Debug, Clone, Serialize)]
pub struct FitSummary {
    /// Model name.
    pub model: &'static str,
    /// Dimensionless cost.
    pub cost: f64,
    /// RMS of | |a| - 1 g | over the positions, in mg.
    pub rms_mg: f64,
    /// Every parameter with its standard errors, written by name as `fit --json` writes them.
    #[serde(serialize_with = "parameters_by_name")]
    pub parameters: Vec<Parameter>,
    /// What the fit warns about.
    pub warnings: Vec<String>,
}

/// The plots; the sections later issues add are `None` until a session carries them.
#[derive(Debug, Clone, Serialize)]
pub struct Figures {
    /// The positions seen down the z axis.
    pub sphere_xy: Figure,
    /// The positions seen along the y axis.
    pub sphere_xz: Figure,
    /// Each position's residual, raw and calibrated.
    pub residuals: [Figure; 2],
    /// The verification's orientations, raw and calibrated with the noise floor.
    pub verification: Option<[Figure; 2]>,
    /// The temperature model and the bins it came from.
    pub temperature: Option<Figure>,
    /// The Allan deviation.
    pub allan_deviation: Option<Figure>,
    /// The gyro's turns.
    pub gyro_turns: Option<Figure>,
}

impl SessionReport {
    /// Fits the session as its calibration was fitted (every model compared) and gathers the report.
    pub fn new(session: &Session) -> Result<Self, FitError> {
        let fitted = session.fitted();
        let fit_report = FitReport::new(&fitted.captures, fitted.model, &FitOptions::default())?;
        let positions = positions(session, &fitted.captures, &fit_report);
        let fit = summary(&fit_report, &positions);
        let verification = session.verification.clone();
        let mut figures = Figures::new(&positions, &fit_report, verification.as_ref());
        figures.gyro_turns = session.gyro_turns.as_deref().map(super::gyro::turns_figure);
        Ok(SessionReport {
            board: Board::of(session),
            verdict: Verdict::new(&fit, verification.as_ref()),
            figures,
            gyro_turns: session.gyro_turns.clone(),
            uploaded: session.uploaded.as_ref().map(Uploaded::of),
            positions,
            fit,
            comparison: fit_report.comparison,
            verification,
            temperature: None,
            allan_deviation: None,
        })
    }

    /// Adds the temperature section and its plot.
    pub fn with_temperature(mut self, section: TemperatureSection, plot: Figure) -> Self {
        self.temperature = Some(section);
        self.figures.temperature = Some(plot);
        self
    }

    /// Adds the Allan deviation section and its plot.
    pub fn with_allan_deviation(mut self, section: AllanSection, plot: Figure) -> Self {
        self.allan_deviation = Some(section);
        self.figures.allan_deviation = Some(plot);
        self
    }
}

/// Each position's reading as taken and as calibrated: by the record uploaded to the board when the
/// session holds it, else by the refit of `fitted`, the readings the fit took (an adaptive
/// session's with the drift taken out, as the chip's temperature model does).
fn positions(session: &Session, fitted: &Dataset, report: &FitReport) -> Vec<PositionResult> {
    let (matrix, offset) = (&report.fit.matrix, &report.fit.offset);
    let calibrated: Vec<[f64; 3]> = match &session.uploaded {
        Some(record) => super::uploaded::calibrated_by(record, session),
        None => mutant!(
            "report-refit-drift-left-in",
            fitted.rows.iter().map(|row| linalg::mul_vec(matrix, linalg::sub(row.reading, *offset))).collect(),
            session
                .captures
                .iter()
                .map(|c| linalg::mul_vec(matrix, linalg::sub(c.stats.mean_g.map(f64::from), *offset)))
                .collect()
        ),
    };
    session
        .captures
        .iter()
        .zip(calibrated)
        .map(|(taken, calibrated_g)| {
            let raw_g = taken.stats.mean_g.map(f64::from);
            PositionResult {
                name: taken.name.clone(),
                raw_g,
                calibrated_g,
                residual_before_mg: residual_mg(raw_g),
                residual_after_mg: residual_mg(calibrated_g),
            }
        })
        .collect()
}

fn summary(report: &FitReport, positions: &[PositionResult]) -> FitSummary {
    let squares: f64 = positions.iter().map(|p| p.residual_after_mg.powi(2)).sum();
    FitSummary {
        model: report.fit.model.name(),
        cost: report.fit.cost,
        rms_mg: (squares / positions.len().max(1) as f64).sqrt(),
        parameters: report.fit.parameters.clone(),
        warnings: report.fit.warnings.clone(),
    }
}

impl Verdict {
    fn new(fit: &FitSummary, verification: Option<&Verification>) -> Self {
        let Some(v) = verification else {
            let line = format!(
                "fitted ({}): | |a| - 1 g | rms {:.3} mg over the positions; not verified at fresh orientations",
                fit.model, fit.rms_mg
            );
            return Verdict { trusted: false, line };
        };
        let trusted = v.trusted();
        let judged = if trusted { "trusted" } else { "not trusted" };
        let line = format!(
            "{judged}: | |a| - 1 g | rms {:.3} mg at {} fresh orientations (noise floor {:.3} mg; {:.2} mg uncalibrated)",
            v.after_rms_mg, v.positions, v.noise_floor_mg, v.before_rms_mg
        );
        Verdict { trusted, line }
    }
}

impl Figures {
    fn new(positions: &[PositionResult], report: &FitReport, verification: Option<&Verification>) -> Self {
        let fit = &report.fit;
        Figures {
            sphere_xy: figure::sphere_view(positions, fit, [0, 1]),
            sphere_xz: figure::sphere_view(positions, fit, [0, 2]),
            residuals: figure::residuals(positions),
            verification: verification.and_then(figure::verification),
            temperature: None,
            allan_deviation: None,
            gyro_turns: None,
        }
    }
}

#[cfg(test)]
mod tests;
