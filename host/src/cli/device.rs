//! Opening the device a command names: a serial port, or a simulated board in this process (with
//! the tool's own hand on it).

use std::sync::Arc;
use std::time::{Duration, Instant};

use super::args::Device;
use crate::error::Error;
use crate::limits::{LISTEN_FIRST, SIM_WAIT_LIMIT};
use crate::link::{
    find_board, open_listening, open_port, resolve_port, serial_ports, Connection, PortOpened, SerialPortEntry,
    TalkingPort,
};
use crate::procedure::{BoardClock, Fixture, Hand, PersonHand, Seat, TimedMember};
use crate::sim::SimulatedHand;
use crate::sim::{Pull, SimBoard, SimulatedMember};

/// An open device, and the simulated board behind it when there is one.
pub(super) struct Opened {
    /// The session with the device.
    pub connection: Connection,
    /// The in-process simulated board, for `--sim`.
    pub sim: Option<SimBoard>,
    /// When the device was opened: a real board's clock starts here, once per run.
    opened_at: Instant,
    /// The seed of the tool's hand on the simulated board (its placement errors and fresh orientations).
    pub hand_seed: u64,
    /// Its place on the fixture that holds it (alone, unless several boards are calibrated together).
    pub seat: Seat,
}

impl Device {
    /// Opens the device, or, when its port talks on its own, hands the port over unwritten.
    pub(super) fn open_or_talking(&self) -> Result<Result<Opened, Box<TalkingPort>>, Error> {
        match &self.port {
            Some(name) => match open_listening(&resolve_port(name, serial_ports)?, self.baud)? {
                PortOpened::Board(connection) => Ok(Ok(Opened::new(*connection, None, self.seed))),
                PortOpened::Talking(talking) => Ok(Err(Box::new(talking))),
            },
            None => self.open().map(Ok),
        }
    }

    /// Opens the device and says hello.
    pub(super) fn open(&self) -> Result<Opened, Error> {
        match (&self.port, self.sim) {
            (Some(name), _) => {
                let connection = open_port(&resolve_port(name, serial_ports)?, self.baud)?;
                Ok(Opened::new(connection, None, self.seed))
            }
            (None, true) => {
                let part = self.sim_part.part(self.sim_faulty_axis);
                let (connection, board) =
                    SimBoard::in_process_part((self.seed, self.sim_sensor.unwrap_or_default(), part))?;
                Ok(Opened::new(connection, Some(board), self.seed))
            }
            (None, false) => {
                let connection = find_board(&serial_ports()?, &mut asking)?;
                Ok(Opened::new(connection, None, self.seed))
            }
        }
    }
}

impl Opened {
    /// A device just opened, alone on its fixture.
    pub(super) fn new(connection: Connection, sim: Option<SimBoard>, seed: u64) -> Self {
        Opened { connection, sim, opened_at: Instant::now(), hand_seed: seed, seat: Fixture::alone().seat(0) }
    }

    /// This board, board `index` of its fixture, as the fixture keeps its time (none for a real
    /// board), its cable pulled when `pull` names it.
    pub(super) fn as_member(&self, index: usize, pull: Option<Pull>) -> Option<Box<dyn TimedMember>> {
        let member = |board: &SimBoard| SimulatedMember::new(index, self.clock(), board.controls(), pull);
        self.sim.as_ref().map(|board| Box::new(member(board)) as Box<dyn TimedMember>)
    }

    /// The board's clock: the simulated board's own time, or for a real one the wall clock since
    /// the device was opened (the same clock however often it is asked for).
    pub(super) fn clock(&self) -> BoardClock {
        match &self.sim {
            Some(board) => Arc::new(board.clock()),
            None => {
                let start = self.opened_at;
                Arc::new(move || start.elapsed().as_secs_f64())
            }
        }
    }

    /// Who turns the board, and how long to wait for it: a person (as long as they take), or the
    /// tool's own hand on the simulated board, off by `placement_deg`, seeded by `hand_seed`,
    /// turning it as a person does; on a fixture of several boards, one hand for all.
    pub(super) fn hand(&self, placement_deg: f64) -> (Box<dyn Hand>, Option<Duration>) {
        hand_for(self.sim.as_ref(), &self.seat, self.hand_seed, placement_deg)
    }
}

/// [`Opened::hand`] from the parts of an opened device it needs, for a caller that holds its
/// connection meanwhile.
pub(super) fn hand_for(
    sim: Option<&SimBoard>,
    seat: &Seat,
    hand_seed: u64,
    placement_deg: f64,
) -> (Box<dyn Hand>, Option<Duration>) {
    match sim {
        Some(board) => {
            let hand = SimulatedHand::new(board.controls(), placement_deg, hand_seed);
            (Box::new(seat.hand(Box::new(hand), false)), Some(SIM_WAIT_LIMIT))
        }
        None => (Box::new(seat.hand(Box::new(PersonHand), true)), None),
    }
}

/// The progress line before a port is asked (which takes over a second).
pub(super) fn asking(port: &SerialPortEntry) {
    let (vendor, product) = port.usb_ids.unwrap_or_default();
    eprintln!(
        "asking {} (USB {vendor:04x}:{product:04x}, not accelcal's ids): listening {:.1} s first, then accelcal's hello",
        port.path,
        LISTEN_FIRST.as_secs_f64()
    );
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::SimSensor;

    #[test]
    fn a_real_boards_clock_counts_from_when_it_was_opened_however_often_it_is_asked_for() {
        let (connection, _board) = SimBoard::in_process(1, SimSensor::Settled).unwrap();
        let opened_at = Instant::now() - Duration::from_secs(5);
        // NOTE: a board behind a port: no simulated clock, the wall clock since it was opened.
        let opened = Opened { opened_at, ..Opened::new(connection, None, 1) };
        let (first, second) = (opened.clock(), opened.clock());
        assert!(first() >= 5.0 && second() >= 5.0, "{} s and {} s since it was opened 5 s ago", first(), second());
        assert!((second() - first()).abs() < 0.5);
    }
}
