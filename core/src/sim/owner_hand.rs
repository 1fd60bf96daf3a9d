//! The owner's commands on the simulated sensor itself (placing, turning, tipping, motion, the
//! surroundings, the wire), wherever the sensor is served: beside the firmware library in this
//! process (the host's threaded `serve`, the core's [`super::board`]), or on the emulated Pico's I2C
//! bus (the host's `emulated`).

use firmware::sim::SimMpu6050;

use super::command::SimCommand;
use super::turn::{tip, turn_between};

/// The hand on the simulated sensor: what it was told, and when a timed motion ends.
#[derive(Debug, Default)]
pub struct OwnerHand {
    /// Sensor time at which a timed motion stops, in microseconds.
    motion_ends_us: Option<u64>,
}

impl OwnerHand {
    /// Applies a command to the sensor; `false` for one that is not the sensor's (the link's, the
    /// board's), which the caller handles.
    pub fn obey(&mut self, sensor: &mut SimMpu6050, command: SimCommand) -> bool {
        // NOTE: only a new motion replaces a timed one; a change of the surroundings during a turn
        // leaves the turn to end where it would have.
        if starts_motion(&command) {
            self.motion_ends_us = None;
        }
        match as_motion(sensor, command) {
            SimCommand::Place(up) => sensor.place(up),
            SimCommand::Move(motion) => sensor.set_motion(motion),
            SimCommand::MoveFor { motion, seconds } => {
                sensor.set_motion(motion);
                self.motion_ends_us = Some(sensor.now_us() + (f64::from(seconds) * 1e6) as u64);
            }
            SimCommand::Connect(connected) => sensor.set_connected(connected),
            SimCommand::Ambient { target_c, c_per_s } => sensor.physics.environment.ramp_to(target_c, c_per_s),
            SimCommand::Elapse(seconds) => soak(sensor, seconds),
            SimCommand::Wait(seconds) => sensor.wait_seconds(seconds),
            _ => return false,
        }
        true
    }

    /// Lets `microseconds` of sensor time pass, ending a timed motion when it is due.
    pub fn advance(&mut self, sensor: &mut SimMpu6050, microseconds: u64) {
        sensor.advance_us(microseconds);
        if self.motion_ends_us.is_some_and(|end| sensor.now_us() >= end) {
            self.motion_ends_us = None;
            sensor.stop_motion();
        }
    }
}

/// Whether `command` starts a new motion (which replaces a timed one).
fn starts_motion(command: &SimCommand) -> bool {
    matches!(
        command,
        SimCommand::Place(_)
            | SimCommand::Move(_)
            | SimCommand::MoveFor { .. }
            | SimCommand::TurnTo(_)
            | SimCommand::Tip(_)
    )
}

/// A turn or a tip as the motion that makes it, from where the sensor rests now (a turn still
/// running ends where it got to); any other command as it is.
fn as_motion(sensor: &mut SimMpu6050, command: SimCommand) -> SimCommand {
    match command {
        SimCommand::TurnTo(up) => {
            sensor.stop_motion();
            let from = sensor.physics.up.map(f64::from);
            turn_between(from, up.map(f64::from), [1.0, 0.0, 0.0])
        }
        SimCommand::Tip(degrees) => {
            sensor.stop_motion();
            tip(sensor.physics.up.map(f64::from), f64::from(degrees))
        }
        command => command,
    }
}

/// Lets `seconds` pass in steps short enough for a ramp of the surroundings to stay smooth.
fn soak(sensor: &mut SimMpu6050, seconds: f32) {
    const STEP_S: f32 = 5.0;
    let mut left = seconds;
    while left > 0.0 {
        sensor.elapse_seconds(left.min(STEP_S));
        left -= STEP_S;
    }
}
