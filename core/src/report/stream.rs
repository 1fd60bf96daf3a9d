//! A fit of a board's own stream (`accelcal fit LOG` on a raw log, `calibrate` on a port that
//! talks on its own): what the stream is, the still periods found in it, what it costs, the gyro's
//! bias, and the fit of the periods' means; as text and as the JSON of DESIGN.md.

use std::fmt::Write;

use serde::Serialize;

use super::json::FitJson;
use super::FitReport;
use crate::fit::gyro::GyroFit;
use crate::fit::{self, FitError, FitOptions, ModelChoice};
use crate::session::Verification;
use crate::stream::cost::{costs, Cost};
use crate::stream::kept;
use crate::stream::plausible::gyro_doubt;
use crate::stream::timing::Rate;
use crate::stream::turns::{self, TurnsFit};
use crate::stream::{AccelUnit, Dialect, Dropped, GyroUnit, SegmentLines, StillPeriods, StreamLog};

mod verify;

/// Why a stream's still periods were not fitted.
#[derive(Debug, thiserror::Error)]
pub enum StreamFitError {
    /// The gyro's values are not in the unit they are read in (so no period rests by it).
    #[error("{0}")]
    GyroUnit(String),
    /// The periods found do not fit.
    #[error("{0}; rest the board at 9 or more orientations for a few seconds each")]
    Periods(FitError),
}

/// A stream's fit and everything its renderers show.
#[derive(Debug, Clone)]
pub struct StreamReport {
    /// The dialect.
    pub dialect: Dialect,
    /// The accelerometer's unit: the calibration applies to values in it.
    pub input_unit: AccelUnit,
    /// The gyro's unit, and whether it was assumed.
    pub gyro_unit: Option<(GyroUnit, bool)>,
    /// The rate, when known.
    pub rate: Option<Rate>,
    /// Samples read.
    pub samples: usize,
    /// Lines that were not samples.
    pub dropped: Dropped,
    /// The still periods, by line.
    pub segments: Vec<SegmentLines>,
    /// What the stream costs.
    pub costs: Vec<Cost>,
    /// The gyro's bias in deg/s.
    pub gyro_bias_dps: Option<[f64; 3]>,
    /// The fit of the periods' means (output in g).
    pub fit: FitReport,
    /// The fit checked at the fresh orientations held out of it, when there were any.
    pub verification: Option<Verification>,
    /// The gyro's G from the turns between the still periods, when the stream has a gyro.
    pub gyro_turns: Option<TurnsFit>,
}

impl StreamReport {
    /// Finds the still periods of `log` and fits `choice` to their means, shown in the stream's unit.
    /// A gyro whose values are not in the unit they are read in is named before the periods are.
    pub fn new(log: &StreamLog, choice: ModelChoice, options: &FitOptions) -> Result<Self, StreamFitError> {
        let still = StillPeriods::of(log);
        let options = FitOptions { g: 1.0, ..options.clone() };
        let doubt = gyro_doubt(log);
        // NOTE: fitted to the rows the stream's session keeps (in g), so that the session's outcome
        // (its certificate, export and report) is this very fit, here restated in the stream's unit.
        let fitted =
            fit::fit(&kept::fitted_rows(log, &still), choice, &options).map_err(|fit| match doubt.clone() {
                Some(doubt) => StreamFitError::GyroUnit(doubt),
                None => StreamFitError::Periods(fit),
            })?;
        let fit = FitReport::of(&still.dataset, fitted.in_unit(log.accel_unit.per_g()), choice, &options);
        let verification = verify::verification(&fit.fit, &still.held_out.rows, log.accel_unit.per_g());
        let gyro_turns = log.gyro_unit.map(|(unit, assumed)| match doubt {
            Some(doubt) => TurnsFit { fit: Err(doubt), range: None },
            None => turns::fit(turns::turns(log, &still.segments, &fit.fit), unit, assumed),
        });
        Ok(StreamReport {
            gyro_turns,
            verification,
            dialect: log.layout.dialect,
            input_unit: log.accel_unit,
            gyro_unit: log.gyro_unit,
            rate: log.rate,
            samples: log.samples.len(),
            dropped: log.dropped.clone(),
            costs: costs(log, &still.segments),
            gyro_bias_dps: still.gyro_bias_dps(),
            segments: still.lines,
            fit,
        })
    }

    /// The gyro's bias in the stream's own unit.
    pub fn gyro_bias(&self) -> Option<[f64; 3]> {
        let (unit, _) = self.gyro_unit?;
        self.gyro_bias_dps.map(|b| b.map(|v| v * unit.per_dps()))
    }
}

/// The object `fit LOG --json` and `calibrate --json` on a foreign stream print.
#[derive(Debug, Serialize)]
pub struct StreamJson<'a> {
    dialect: Dialect,
    input_unit: AccelUnit,
    gyro_unit: Option<GyroUnit>,
    gyro_unit_assumed: bool,
    rate_hz: Option<f64>,
    rate_source: Option<crate::stream::timing::RateSource>,
    samples: usize,
    dropped: &'a Dropped,
    segments: &'a [SegmentLines],
    costs: &'a [Cost],
    gyro_bias: Option<[f64; 3]>,
    gyro_bias_dps: Option<[f64; 3]>,
    verification: Option<&'a Verification>,
    gyro_fit: Option<&'a GyroFit>,
    gyro_not_fitted: Option<&'a str>,
    gyro_range: Option<&'a str>,
    #[serde(flatten)]
    fit: FitJson<'a>,
}

/// `--json`: the report as pretty JSON.
pub fn json(report: &StreamReport) -> String {
    let view = StreamJson {
        dialect: report.dialect,
        input_unit: report.input_unit,
        gyro_unit: report.gyro_unit.map(|(unit, _)| unit),
        gyro_unit_assumed: report.gyro_unit.is_some_and(|(_, assumed)| assumed),
        rate_hz: report.rate.map(|r| crate::shown::hz_value(r.hz)),
        rate_source: report.rate.map(|r| r.source),
        samples: report.samples,
        dropped: &report.dropped,
        segments: &report.segments,
        costs: &report.costs,
        gyro_bias: report.gyro_bias(),
        gyro_bias_dps: report.gyro_bias_dps,
        verification: report.verification.as_ref(),
        gyro_fit: report.gyro_turns.as_ref().and_then(|g| g.fit.as_ref().ok()),
        gyro_not_fitted: report.gyro_turns.as_ref().and_then(|g| g.fit.as_ref().err()).map(String::as_str),
        gyro_range: report.gyro_turns.as_ref().and_then(|g| g.range.as_deref()),
        fit: FitJson::new(&report.fit),
    };
    serde_json::to_string_pretty(&view).unwrap_or_default()
}

/// The report for a person: the stream, its still periods and costs, then the fit.
pub fn text(report: &StreamReport) -> String {
    let mut out = String::new();
    write_stream(&mut out, report);
    let _ = writeln!(out, "{} still periods:", report.segments.len());
    for s in &report.segments {
        let role = if s.verifies { ", verifies (a fresh orientation)" } else { "" };
        let _ = writeln!(
            out,
            "  lines {:>6}-{:<6} {:>5} samples, scatter {:.2} mg{role}",
            s.first_line, s.last_line, s.samples, s.scatter_mg
        );
    }
    if let Some(bias) = report.gyro_bias_dps {
        let _ = writeln!(out, "gyro bias {:+.3} {:+.3} {:+.3} deg/s", bias[0], bias[1], bias[2]);
    }
    if let Some(gyro) = &report.gyro_turns {
        write_gyro_turns(&mut out, gyro);
    }
    for cost in &report.costs {
        let _ = writeln!(out, "cost: {}", cost.words);
    }
    let unit = report.input_unit.name();
    let _ = writeln!(
        out,
        "M and o apply to the values as the sketch prints them: a = M (m - o), a in g, m and o in {unit}"
    );
    out + &super::text::fit_report(&report.fit) + &verified(report.verification.as_ref())
}

/// The verification at fresh orientations in words.
pub fn verified(verification: Option<&Verification>) -> String {
    match verification {
        Some(v) => format!(
            "verified at {} fresh orientations held out of the fit: | |a| - 1 g | rms {:.2} mg before, {:.3} mg after \
             (worst {:.3} mg); the means' own noise {:.3} mg, {}\n",
            v.positions,
            v.before_rms_mg,
            v.after_rms_mg,
            v.after_max_mg,
            v.noise_floor_mg,
            if v.trusted() { "the error is within that noise" } else { "more than that noise explains" }
        ),
        None => "not verified: no still period at a fresh orientation (away from every face and corner) was held out\n"
            .to_owned(),
    }
}

fn write_gyro_turns(out: &mut String, gyro: &TurnsFit) {
    let _ = match &gyro.fit {
        Ok(g) => writeln!(
            out,
            "gyro G from {} turns: scale {:.4} {:.4} {:.4}, residual {:.3} deg (w = G (w_raw - b))",
            g.turns, g.matrix[0][0], g.matrix[1][1], g.matrix[2][2], g.residual_deg
        ),
        Err(why) => writeln!(out, "gyro G not fitted: {why}"),
    };
    if let Some(range) = &gyro.range {
        let _ = writeln!(out, "{range}");
    }
}

fn write_stream(out: &mut String, report: &StreamReport) {
    let gyro = match report.gyro_unit {
        Some((unit, true)) => format!(", gyro in {} (assumed: --gyro-unit settles it)", unit.name()),
        Some((unit, false)) => format!(", gyro in {}", unit.name()),
        None => ", no gyro".to_owned(),
    };
    let rate = match report.rate {
        Some(rate) => format!("{:.1} Hz from {}", rate.hz, rate_source(rate)),
        None => "rate unknown (no timestamps)".to_owned(),
    };
    let _ =
        writeln!(out, "stream: {}, accelerometer in {}{gyro}, {rate}", report.dialect.name(), report.input_unit.name());
    let _ = writeln!(out, "{} samples; {} lines dropped", report.samples, report.dropped.total());
    for d in &report.dropped.0 {
        let _ = writeln!(out, "  {} line(s) from line {}: {}", d.lines, d.first_line, d.reason.words());
    }
}

fn rate_source(rate: Rate) -> &'static str {
    match rate.source {
        crate::stream::timing::RateSource::Timestamps => "its timestamps",
        crate::stream::timing::RateSource::ArrivalTimes => "the lines' arrival",
        crate::stream::timing::RateSource::Given => "--rate",
    }
}
