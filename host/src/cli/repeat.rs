//! `accelcal repeat N`: N calibrations of one simulated board with a power cycle between them, and
//! each parameter's spread beside the standard error the sessions predicted.

use indicatif::{ProgressBar, ProgressStyle};

use super::args::RepeatArgs;
use crate::error::Error;
use crate::limits::DEFAULT_TARGET_MG;
use crate::repeat::{self, RepeatOptions, RepeatReport};
use crate::sim::SimulatedSession;

/// Runs `accelcal repeat`.
pub(super) fn repeat(args: &RepeatArgs) -> Result<(), Error> {
    if !args.device.sim {
        return Err(Error::RepeatNeedsSim);
    }
    let options = RepeatOptions {
        sessions: usize::from(args.sessions),
        seed: args.device.seed,
        sensor: args.device.sim_sensor.unwrap_or_default(),
        turn_on_bias_g: args.sim_turn_on_bias_mg * 1e-3,
        session: SimulatedSession { placement_deg: 3.0, hand_seed: args.device.seed, target_mg: DEFAULT_TARGET_MG },
    };
    let bar = ProgressBar::new(u64::from(args.sessions)).with_style(
        ProgressStyle::with_template("calibrating after power cycle {pos}/{len} {bar:30} {elapsed}")
            .unwrap_or(ProgressStyle::default_bar()),
    );
    let mut runs = Vec::with_capacity(options.sessions);
    for cycle in 0..options.sessions as u64 {
        runs.push(repeat::run(&options, cycle)?);
        bar.inc(1);
    }
    bar.finish_and_clear();
    let report = RepeatReport::of(&options, runs);
    match args.json {
        true => println!("{}", serde_json::to_string_pretty(&report).unwrap_or_default()),
        false => print!("{}", text(&report)),
    }
    Ok(())
}

/// The report as a table: per parameter mean, spread, predicted spread, their ratio and the excess.
fn text(report: &RepeatReport) -> String {
    let mut out = format!(
        "{} calibrations of one board, a power cycle before each (turn-on bias injected: {} mg)\n",
        report.sessions, report.turn_on_bias_injected_mg
    );
    out.push_str(&format!(
        "{:<6} {:>12} {:>11} {:>11} {:>13} {:>11}\n",
        "", "mean", "std", "predicted", "ratio", "excess"
    ));
    for (name, p) in &report.parameters {
        out.push_str(&format!(
            "{name:<6} {:>12.6} {:>11.3e} {:>11.3e} {:>6.2} +- {:<4.2} {:>11.3e} {}\n",
            p.mean, p.std, p.predicted_std, p.ratio, p.ratio_sampling_error, p.excess, p.unit
        ));
    }
    out.push_str("ratio = std / predicted: 1 within its +- when the model leaves nothing out; excess = sqrt(std^2 - predicted^2)\n");
    out
}
