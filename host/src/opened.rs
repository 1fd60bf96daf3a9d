//! A board opened for a run: its connection, the simulated board behind it when there is one, its
//! seat on the fixture that holds it, its clock (a real board's counts from when it was opened), the
//! hand that turns it (the person's, or the tool's own on a simulated board) and the report of its
//! run, with the simulated truth beside it.

use std::sync::Arc;
use std::time::{Duration, Instant};

use crate::calibration;
use crate::limits::SIM_WAIT_LIMIT;
use crate::link::Connection;
use crate::procedure::{BoardClock, Fitted, Fixture, Hand, PersonHand, Seat, TimedMember, TurnCheck, Verification};
use crate::report::CalibrateReport;
use crate::sim::SimulatedHand;
use crate::sim::{Pull, SimBoard, SimulatedMember};

/// An open device, and the simulated board behind it when there is one.
pub struct Opened {
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

impl Opened {
    /// A device just opened, alone on its fixture.
    pub fn new(connection: Connection, sim: Option<SimBoard>, seed: u64) -> Self {
        Opened { connection, sim, opened_at: Instant::now(), hand_seed: seed, seat: Fixture::alone().seat(0) }
    }

    /// This board, board `index` of its fixture, as the fixture keeps its time (none for a real
    /// board), its cable pulled when `pull` names it.
    pub fn as_member(&self, index: usize, pull: Option<Pull>) -> Option<Box<dyn TimedMember>> {
        let member = |board: &SimBoard| SimulatedMember::new(index, self.clock(), board.controls(), pull);
        self.sim.as_ref().map(|board| Box::new(member(board)) as Box<dyn TimedMember>)
    }

    /// The board's clock: the simulated board's own time, or for a real one the wall clock since
    /// the device was opened (the same clock however often it is asked for).
    pub fn clock(&self) -> BoardClock {
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
    pub fn hand(&self, placement_deg: f64) -> (Box<dyn Hand>, Option<Duration>) {
        hand_for(self.sim.as_ref(), &self.seat, self.hand_seed, placement_deg)
    }

    /// The run's report: the calibration chosen, the fits beside it, the verification and the gyro's
    /// check, and with `--sim` the simulated sensor's truth at the calibration's temperature.
    pub fn report(&self, fitted: &Fitted, verification: Verification, check: Option<TurnCheck>) -> CalibrateReport {
        let session_temp_c = calibration::thermal_reference(&fitted.chosen).ref_temp_c;
        let truth = self.sim.as_ref().map(|board| board.truth_json(session_temp_c));
        let captures = fitted.session.captures.len();
        let chip = fitted.chip.as_ref().map(|c| &c.calibration);
        let mut report =
            CalibrateReport::new(&fitted.chosen, chip, fitted.host.as_ref(), truth, verification, captures)
                .with_gyro(&fitted.gyro, check);
        report.true_error_mg = self.sim.as_ref().map(|board| board.true_error_mg(&fitted.chosen, session_temp_c));
        report
    }
}

/// Seats boards on one fixture, in order; `None` is a board that could not be opened, which
/// leaves the fixture at once. A simulated board's time is kept by the fixture, its cable pulled
/// as `pull` says.
pub fn seat_together(mut boards: Vec<Option<&mut Opened>>, pull: Option<Pull>) {
    let members = boards.iter().enumerate().map(|(index, board)| board.as_ref().and_then(|o| o.as_member(index, pull)));
    let fixture = Fixture::new(members.collect());
    for (index, board) in boards.iter_mut().enumerate() {
        // NOTE: taken for every board, so that one not opened leaves at once (its seat dropped here).
        let seat = fixture.seat(index);
        if let Some(opened) = board {
            opened.seat = seat;
        }
    }
}

/// [`Opened::hand`] from the parts of an opened device it needs, for a caller that holds its
/// connection meanwhile.
pub fn hand_for(
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
