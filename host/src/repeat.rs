//! `accelcal repeat N` (issue 28): N calibrations of one simulated board with a power cycle between
//! them, every parameter's mean and standard deviation beside the standard error each session
//! predicted from its own captures. Their ratio says whether something the model leaves out (a
//! turn-on bias, temperature, placement) is there; the excess sqrt(std^2 - predicted^2) says how much.

use std::collections::BTreeMap;

use serde::Serialize;

use crate::certificate::{Certificate, Component};
use crate::error::Error;
use crate::fit::drift;
use crate::sim::SimulatedSession;
use crate::sim::{PowerOn, SimBoard, SimSensor};
use firmware::sim::part::SimPart;

/// What to repeat.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RepeatOptions {
    pub sessions: usize,
    /// The simulated board (its serial and its noise).
    pub seed: u64,
    pub sensor: SimSensor,
    /// The turn-on bias repeatability injected at each power-on, standard deviation in g.
    pub turn_on_bias_g: f64,
    pub session: SimulatedSession,
}

/// The repeatability of every parameter over the sessions.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RepeatReport {
    pub sessions: usize,
    pub serial: Option<String>,
    /// The turn-on bias injected into the simulation (standard deviation, mg).
    pub turn_on_bias_injected_mg: f64,
    pub parameters: BTreeMap<String, Repeatability>,
    /// Each session's parameters, standard errors and (simulated) true offset.
    pub runs: Vec<Run>,
}

/// One parameter over the sessions, in the certificate's unit.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Repeatability {
    pub unit: String,
    /// Sessions whose fit has the parameter.
    pub sessions: usize,
    pub mean: f64,
    /// Sample standard deviation over the sessions.
    pub std: f64,
    /// RMS over the sessions of each one's standard error from its own captures (noise, quantisation).
    pub predicted_std: f64,
    /// std / predicted_std: 1 within `ratio_sampling_error` when nothing is left out.
    pub ratio: f64,
    /// The ratio's own standard error from the number of sessions, ratio / sqrt(2 (n - 1)).
    pub ratio_sampling_error: f64,
    /// sqrt(std^2 - predicted_std^2) where std is the larger (else 0): what the model leaves out.
    pub excess: f64,
    /// RMS of the certificates' whole standard uncertainty u (every component of the budget).
    pub certificate_u: f64,
}

/// One session of the repeat.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Run {
    /// Which power-on (0: the first).
    pub cycle: u64,
    pub values: BTreeMap<String, f64>,
    /// The session's standard error of each parameter from its own captures.
    pub predicted: BTreeMap<String, f64>,
    /// Each certificate's u.
    pub certificate_u: BTreeMap<String, f64>,
    /// The simulated sensor's true offset at the session's mean temperature, in g.
    pub true_offset_g: [f64; 3],
    /// The board's serial, as its certificate states it.
    #[serde(skip)]
    pub serial: Option<String>,
}

/// One session: the board powered on for the `cycle`-th time, calibrated, its certificate's figures.
pub fn run(options: &RepeatOptions, cycle: u64) -> Result<Run, Error> {
    let power = PowerOn { cycle, turn_on_bias_g: options.turn_on_bias_g as f32 };
    let sensor = (options.seed, options.sensor, SimPart::mpu6050());
    let (mut connection, board) = SimBoard::in_process_powered(sensor, power)?;
    let hand_seed = options.session.hand_seed.wrapping_add(cycle);
    let session = board.collect_session(&SimulatedSession { hand_seed, ..options.session }, &mut connection)?;
    let certificate = Certificate::issue(&session)?;
    let reading_c = drift::mean_temp_c(&session.dataset()) as f32;
    let true_offset_g = board.truth_at(reading_c).offset_g.map(f64::from);
    let own = |p: &crate::certificate::CertifiedValue| {
        let part = |c: Component| p.budget.get(&c).copied().unwrap_or(0.0);
        part(Component::Noise).hypot(part(Component::Quantisation))
    };
    let each = |f: &dyn Fn(&crate::certificate::CertifiedValue) -> f64| {
        certificate.parameters.iter().map(|(name, p)| (name.clone(), f(p))).collect()
    };
    let (values, predicted, certificate_u) = (each(&|p| p.value), each(&own), each(&|p| p.u));
    Ok(Run { cycle, values, predicted, certificate_u, true_offset_g, serial: certificate.board.serial })
}

impl RepeatReport {
    /// The report of the runs (their certificates' units by name).
    pub fn of(options: &RepeatOptions, runs: Vec<Run>) -> Self {
        let names: std::collections::BTreeSet<&String> = runs.iter().flat_map(|r| r.values.keys()).collect();
        let parameters = names.into_iter().map(|name| (name.clone(), Repeatability::of(name, &runs))).collect();
        RepeatReport {
            sessions: runs.len(),
            serial: runs.first().and_then(|r| r.serial.clone()),
            turn_on_bias_injected_mg: options.turn_on_bias_g * 1e3,
            parameters,
            runs,
        }
    }

    /// The report as a table: per parameter mean, spread, predicted spread, their ratio and the excess.
    pub fn text(&self) -> String {
        let mut out = format!(
            "{} calibrations of one board, a power cycle before each (turn-on bias injected: {} mg)\n",
            self.sessions, self.turn_on_bias_injected_mg
        );
        out.push_str(&format!(
            "{:<6} {:>12} {:>11} {:>11} {:>13} {:>11}\n",
            "", "mean", "std", "predicted", "ratio", "excess"
        ));
        for (name, p) in &self.parameters {
            out.push_str(&format!(
                "{name:<6} {:>12.6} {:>11.3e} {:>11.3e} {:>6.2} +- {:<4.2} {:>11.3e} {}\n",
                p.mean, p.std, p.predicted_std, p.ratio, p.ratio_sampling_error, p.excess, p.unit
            ));
        }
        out.push_str("ratio = std / predicted: 1 within its +- when the model leaves nothing out; excess = sqrt(std^2 - predicted^2)\n");
        out
    }
}

impl Repeatability {
    fn of(name: &str, runs: &[Run]) -> Self {
        let pick = |map: fn(&Run) -> &BTreeMap<String, f64>| -> Vec<f64> {
            runs.iter().filter_map(|r| map(r).get(name).copied()).collect()
        };
        let (values, predicted, stated) = (pick(|r| &r.values), pick(|r| &r.predicted), pick(|r| &r.certificate_u));
        let n = values.len() as f64;
        let mean = values.iter().sum::<f64>() / n;
        let std = (values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
        let rms = |v: &[f64]| (v.iter().map(|x| x * x).sum::<f64>() / v.len() as f64).sqrt();
        let predicted_std = rms(&predicted);
        let ratio = std / predicted_std;
        Repeatability {
            unit: crate::certificate::unit(name).to_owned(),
            sessions: values.len(),
            mean,
            std,
            predicted_std,
            ratio,
            ratio_sampling_error: ratio / (2.0 * (n - 1.0)).sqrt(),
            excess: (std * std - predicted_std * predicted_std).max(0.0).sqrt(),
            certificate_u: rms(&stated),
        }
    }
}
