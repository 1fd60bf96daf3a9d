//! `accelcal thermal`: learns how the sensor drifts with temperature, fits the temperature model
//! around the static calibration and makes it active on the chip: on a person's board
//! (`procedure::thermal::resting`), or with `--sim` the whole simulated story (`sim::thermal`).

use super::args::ThermalArgs;
use crate::error::Error;
use crate::link::LinkError;
use crate::procedure::thermal::resting::{learn_at_rest, RestingOptions};
use crate::sim::thermal::{story, StoryOptions};
use crate::terminal::interrupt_on_ctrl_c;

/// Runs `accelcal thermal`.
pub(super) fn thermal(args: &ThermalArgs) -> Result<(), Error> {
    let mut opened = args.device.open()?;
    opened.connection.info.sensor.map_err(LinkError::from)?;
    let report = match opened.sim.take() {
        Some(board) => story(&mut opened.connection, &board, &story_options(args))?,
        None => learn_at_rest(&mut opened.connection, &resting_options(args), interrupt_on_ctrl_c)?,
    };
    if args.json {
        println!("{}", report.json());
    } else {
        print!("{}", report.text());
    }
    Ok(())
}

/// The simulated story's options.
fn story_options(args: &ThermalArgs) -> StoryOptions {
    let verify_positions = usize::from(args.verify);
    StoryOptions { target_span_c: args.target_span_c, verify_positions, seed: args.device.seed, quiet: args.json }
}

/// A person's run's options.
fn resting_options(args: &ThermalArgs) -> RestingOptions {
    let port = args.device.port.clone().unwrap_or_default();
    RestingOptions { target_span_c: args.target_span_c, bins: args.bins.clone(), port, quiet: args.json }
}
