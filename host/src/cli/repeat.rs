//! `accelcal repeat N`: N calibrations of one simulated board with a power cycle between them, and
//! each parameter's spread beside the standard error the sessions predicted.

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
    let bar = crate::terminal::counting(
        "calibrating after power cycle {pos}/{len} {bar:30} {elapsed}",
        u64::from(args.sessions),
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
        false => print!("{}", report.text()),
    }
    Ok(())
}
