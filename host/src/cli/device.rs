//! Opening the device a command names: a serial port, or a simulated board in this process (with
//! the tool's own hand on it).

use std::sync::Arc;
use std::time::{Duration, Instant};

use clap::Args;

use crate::error::Error;
use crate::limits::{BAUD_RANGE, SIM_WAIT_LIMIT};
use crate::link::port::DEFAULT_BAUD;
use crate::link::{
    find_board, open_listening, open_port, resolve_port, serial_ports, Connection, PortOpened, TalkingPort,
};
use crate::procedure::{BoardClock, Fixture, Hand, PersonHand, Seat, SimulatedHand, SimulatedMember};
use crate::sim::{FaultyAxis, SimBoard, SimPartChoice, SimSensor};

/// Which device to talk to.
#[derive(Args, Clone)]
pub struct Device {
    /// Serial port of the board (see `accelcal ports`), or of `accelcal sim --pty`; or the board's
    /// serial number as `accelcal ports` shows it. Without --port or --sim: the one accelcal board
    /// plugged in (by its USB ids, or by its handshake on a USB port of another identity).
    #[arg(long, conflicts_with = "sim")]
    pub port: Option<String>,
    /// With --port: the baud rate of a UART bridge (the sketch's `Serial.begin`); USB serial ignores it.
    #[arg(long, default_value_t = DEFAULT_BAUD, value_parser = baud, conflicts_with = "sim")]
    pub baud: u32,
    /// A simulated board in this process (its flash lasts as long as the command).
    #[arg(long)]
    pub sim: bool,
    /// With --sim: seed of the simulated sensor's noise and of the hand's placement.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// With --sim: the simulated sensor, realistic (warming and drifting; the default for one board),
    /// settled (one temperature) or drawn (realistic, a part drawn by the seed from the datasheet's
    /// spreads; the default for `calibrate --boards N`).
    #[arg(long, value_enum)]
    pub sim_sensor: Option<SimSensor>,
    /// With --sim: the simulated part (its register map, temperature formula and self-test).
    #[arg(long, value_enum, default_value_t = SimPartChoice::Mpu6050)]
    pub sim_part: SimPartChoice,
    /// With --sim: this axis' self-test response is 20 % off its factory trim.
    #[arg(long, value_enum)]
    pub sim_faulty_axis: Option<FaultyAxis>,
}

/// A baud rate within [`BAUD_RANGE`]; the cause when not.
fn baud(text: &str) -> Result<u32, String> {
    let baud: u32 =
        text.parse().map_err(|_| format!("{text:?} is not a baud rate: give a whole number such as 115200"))?;
    if BAUD_RANGE.contains(&baud) {
        Ok(baud)
    } else {
        Err(format!(
            "{baud} Bd is not in {}-{} Bd: below it no sketch prints a sensor, above it no USB UART bridge goes; \
             give the number in the sketch's Serial.begin",
            BAUD_RANGE.start(),
            BAUD_RANGE.end()
        ))
    }
}

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
                let connection = find_board(&serial_ports()?, &mut super::board::asking)?;
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

    /// This board's time and controls as its fixture keeps them (none for a real board).
    pub(super) fn as_member(&self) -> Option<SimulatedMember> {
        self.sim.as_ref().map(|board| SimulatedMember { clock: self.clock(), controls: board.controls() })
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
        match &self.sim {
            Some(board) => {
                let hand = SimulatedHand::new(board.controls(), placement_deg, self.hand_seed);
                (Box::new(self.seat.hand(Box::new(hand), false)), Some(SIM_WAIT_LIMIT))
            }
            None => (Box::new(self.seat.hand(Box::new(PersonHand), true)), None),
        }
    }
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

    #[test]
    fn a_baud_rate_is_taken_within_what_bridges_go_and_a_nonsense_one_refused_with_its_cause() {
        assert_eq!(baud("38400"), Ok(38_400));
        assert_eq!(baud("300"), Ok(300));
        let zero = baud("0").unwrap_err();
        assert!(zero.contains("0 Bd is not in 300-6000000 Bd") && zero.contains("Serial.begin"), "{zero}");
        assert!(baud("9000000").unwrap_err().contains("no USB UART bridge"));
        assert!(baud("fast").unwrap_err().contains("\"fast\" is not a baud rate"));
    }
}
