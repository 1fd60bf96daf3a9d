//! Opening the device a command names: a serial port, or a simulated board in this process (with
//! the tool's own hand on it).

use std::sync::Arc;
use std::time::Duration;

use super::args::Device;
use crate::error::Error;
use crate::link::{open_port, resolve_port, serial_ports, Connection};
use crate::procedure::{BoardClock, Hand, PersonHand, SimulatedHand};
use crate::sim::SimBoard;

/// How long the tool waits for the simulated board (which it turns itself) to settle.
const SIM_WAIT_LIMIT: Duration = Duration::from_secs(60);

/// An open device, and the simulated board behind it when there is one.
pub(super) struct Opened {
    /// The session with the device.
    pub connection: Connection,
    /// The in-process simulated board, for `--sim`.
    pub sim: Option<SimBoard>,
}

impl Device {
    /// Opens the device and says hello.
    pub(super) fn open(&self) -> Result<Opened, Error> {
        match (&self.port, self.sim) {
            (Some(name), _) => Ok(Opened { connection: open_port(&resolve_port(name, serial_ports)?)?, sim: None }),
            (None, true) => {
                let part = self.sim_part.part(self.sim_faulty_axis);
                let (connection, board) = SimBoard::in_process_part((self.seed, self.sim_sensor, part))?;
                Ok(Opened { connection, sim: Some(board) })
            }
            (None, false) => Err(Error::WhichDevice),
        }
    }
}

impl Opened {
    /// The board's clock: the simulated board's own time, or the wall clock from now for a real one.
    pub(super) fn clock(&self) -> BoardClock {
        match &self.sim {
            Some(board) => Arc::new(board.clock()),
            None => {
                let start = std::time::Instant::now();
                Arc::new(move || start.elapsed().as_secs_f64())
            }
        }
    }

    /// Who turns the board, and how long to wait for it: a person (as long as they take), or the
    /// tool's own hand on the simulated board, off by `placement_deg`, seeded by `seed`, turning it
    /// as a person does.
    pub(super) fn hand(&self, placement_deg: f64, seed: u64) -> (Box<dyn Hand>, Option<Duration>) {
        match &self.sim {
            Some(board) => {
                let hand = SimulatedHand::new(board.controls(), placement_deg, seed);
                (Box::new(hand), Some(SIM_WAIT_LIMIT))
            }
            None => (Box::new(PersonHand), None),
        }
    }
}
