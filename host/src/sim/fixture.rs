//! A simulated board on a fixture of several (`calibrate --sim --boards N`): the fixture keeps its
//! time (it waits when the others are slower), and `--sim-pull` pulls its cable at a turn.

use std::sync::mpsc::Sender;

use super::SimCommand;
use crate::procedure::{BoardClock, TimedMember};

/// A simulated pulled cable: `board` (0-based) is unplugged right after its `turn`-th turn (1-based).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Pull {
    pub board: usize,
    pub turn: usize,
}

/// A simulated board of the fixture, as the fixture keeps its time: its clock and its controls, and
/// the turn after which its cable is pulled, if any.
pub struct SimulatedMember {
    clock: BoardClock,
    controls: Sender<SimCommand>,
    pulled_after_turn: Option<usize>,
}

impl SimulatedMember {
    /// Board `index` (0-based) of the fixture, read by `clock` and turned through `controls`; its
    /// cable is pulled when `pull` names it.
    pub fn new(index: usize, clock: BoardClock, controls: Sender<SimCommand>, pull: Option<Pull>) -> Self {
        let pulled_after_turn = pull.filter(|pull| pull.board == index).map(|pull| pull.turn);
        SimulatedMember { clock, controls, pulled_after_turn }
    }
}

impl TimedMember for SimulatedMember {
    fn now_s(&self) -> f64 {
        (self.clock)()
    }

    fn wait(&self, seconds: f64) {
        // NOTE: a board that stopped is found by its own session; nothing to do here.
        let _ = self.controls.send(SimCommand::Wait(seconds as f32));
    }

    fn turned(&self, turns: usize) {
        if self.pulled_after_turn == Some(turns) {
            let _ = self.controls.send(SimCommand::Stop);
        }
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use super::*;

    #[test]
    fn a_member_waits_as_told_and_only_the_pulled_board_stops_after_its_turn() {
        let (controls, commands) = std::sync::mpsc::channel();
        let pull = Some(Pull { board: 1, turn: 3 });
        let pulled = SimulatedMember::new(1, Arc::new(|| 7.5), controls.clone(), pull);
        let other = SimulatedMember::new(0, Arc::new(|| 7.5), controls, pull);
        assert_eq!(pulled.now_s(), 7.5);
        pulled.wait(2.25);
        (1..=4).for_each(|turns| other.turned(turns));
        (1..=4).for_each(|turns| pulled.turned(turns));
        let sent: Vec<SimCommand> = commands.try_iter().collect();
        let expected = [SimCommand::Wait(2.25), SimCommand::Stop];
        assert_eq!(sent, expected, "one wait of 2.25 s, and board 2 pulled after its third turn only");
    }
}
