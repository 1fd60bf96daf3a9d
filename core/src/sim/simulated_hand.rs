//! The tool's own hand on the simulated board: it turns the board through the board's controls
//! handle to each wanted orientation, a few degrees off at random as a person's hand would, and to
//! random orientations for verification. Once the board rests somewhere, it turns it on from there
//! as a hand does (a real rotation at a smoothly rising and falling rate), so that the gyro sees
//! the turn.

use rand_xoshiro::rand_core::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;
use shared::linalg::{add, cross, norm, scale};

use super::command::SimCommand;
use super::random::{gaussian, random_unit};
use super::turn::{turn_between, turning};
use crate::limits::FRESH_DEG;
use crate::run::{Feedback, Hand, Orientation, ProcedureError};

/// How far beyond [`FRESH_DEG`], in degrees, the hand keeps its verification orientations apart,
/// so that its own placement error never makes one look like a repeat.
const FRESH_MARGIN_DEG: f64 = 10.0;
/// Random orientations tried for one clear of those verified before (12 fit easily beside the 14
/// calibration positions; past that the farthest of them is taken).
const FRESH_TRIES: usize = 1000;
/// A verification turn, in degrees: the quarter turn the user is shown.
pub const VERIFICATION_TURN_DEG: f64 = 90.0;

/// The simulated board has stopped: it takes no more commands.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Stopped;

/// How the hand reaches the simulated board: a channel to the host's threaded board, or the core's
/// board in this process.
pub trait Controls {
    /// Applies `command` to the board.
    fn send(&mut self, command: SimCommand) -> Result<(), Stopped>;
}

impl Controls for std::sync::mpsc::Sender<SimCommand> {
    fn send(&mut self, command: SimCommand) -> Result<(), Stopped> {
        std::sync::mpsc::Sender::send(self, command).map_err(|_| Stopped)
    }
}

impl Controls for Box<dyn Controls> {
    fn send(&mut self, command: SimCommand) -> Result<(), Stopped> {
        self.as_mut().send(command)
    }
}

/// The tool's hand on a simulated board.
pub struct SimulatedHand {
    controls: Box<dyn Controls>,
    rng: Xoshiro256PlusPlus,
    placement_deg: f64,
    verified: Vec<[f64; 3]>,
    /// Where the board rests (the up direction in the body frame), once the hand has put it down.
    resting: Option<[f64; 3]>,
}

impl SimulatedHand {
    /// A hand on the board behind `controls`, off by about `placement_deg` (random axis, normal
    /// angle), repeatable by `seed`.
    pub fn new(controls: impl Controls + 'static, placement_deg: f64, seed: u64) -> Self {
        let rng = Xoshiro256PlusPlus::seed_from_u64(seed);
        SimulatedHand { controls: Box::new(controls), rng, placement_deg, verified: Vec::new(), resting: None }
    }

    /// Brings the board to rest with `up` up: turned there from where it rests, else put there.
    fn place(&mut self, up: [f64; 3]) -> Result<(), ProcedureError> {
        let command = match self.resting.replace(up) {
            Some(from) => self.turn_command(from, up),
            None => SimCommand::Place(up.map(|v| v as f32)),
        };
        self.controls.send(command).map_err(|_| ProcedureError::SimulatedBoardStopped)
    }

    /// The turn that carries the body's up from `from` to `to`, about the line perpendicular to
    /// both (horizontal all the way); a half turn goes about a random horizontal line.
    fn turn_command(&mut self, from: [f64; 3], to: [f64; 3]) -> SimCommand {
        turn_between(from, to, random_unit(&mut self.rng))
    }

    /// A quarter turn about a random horizontal line, from where the board rests.
    fn quarter_turn(&mut self) -> Result<(), ProcedureError> {
        let from = self.resting.unwrap_or([0.0, 0.0, 1.0]);
        let axis = cross(from, random_unit(&mut self.rng));
        let axis = scale(axis, 1.0 / norm(axis));
        let angle = VERIFICATION_TURN_DEG.to_radians();
        // Gravity turns the other way in the body frame: up goes to from cos - (axis x from) sin.
        let to = add(scale(from, angle.cos()), scale(cross(axis, from), -angle.sin()));
        self.resting = Some(to);
        let command = turning(axis, VERIFICATION_TURN_DEG);
        self.controls.send(command).map_err(|_| ProcedureError::SimulatedBoardStopped)
    }

    /// `up` tilted by a normally distributed angle about a random axis perpendicular to it.
    fn misplaced(&mut self, up: [f64; 3]) -> [f64; 3] {
        let axis = cross(up, random_unit(&mut self.rng));
        let axis = scale(axis, 1.0 / norm(axis));
        let angle = (self.placement_deg * gaussian(&mut self.rng)).to_radians();
        add(scale(up, angle.cos()), scale(cross(axis, up), angle.sin()))
    }

    /// A new random orientation, well clear of those verified before (a person turns the board
    /// somewhere new; the procedure insists on it): clear by [`FRESH_DEG`] and a margin; when none
    /// of the tries is (many verification positions fill the sphere), the one farthest from them all.
    fn new_orientation(&mut self) -> [f64; 3] {
        let nearest_deg = |up: [f64; 3], verified: &[[f64; 3]]| {
            verified.iter().map(|v| shared::orientation::angle_between_deg(up, *v)).fold(f64::INFINITY, f64::min)
        };
        let mut up = random_unit(&mut self.rng);
        let mut farthest = (up, f64::NEG_INFINITY);
        for _ in 0..FRESH_TRIES {
            let nearest = nearest_deg(up, &self.verified);
            if nearest >= FRESH_DEG + FRESH_MARGIN_DEG {
                return up;
            }
            if nearest > farthest.1 {
                farthest = (up, nearest);
            }
            up = random_unit(&mut self.rng);
        }
        farthest.0
    }
}

impl Hand for SimulatedHand {
    fn present(&mut self, target: &Orientation, _: &mut dyn Feedback) -> Result<(), ProcedureError> {
        let up = self.misplaced(target.up);
        self.place(up)
    }

    fn fresh(&mut self, _: usize, _: &mut dyn Feedback) -> Result<(), ProcedureError> {
        let up = self.new_orientation();
        self.verified.push(up);
        self.place(up)
    }

    fn turn_quarter(&mut self, _: &mut dyn Feedback) -> Result<(), ProcedureError> {
        self.quarter_turn()
    }

    fn avoid(&mut self, orientations: &[[f64; 3]]) {
        self.verified.extend(orientations.iter().map(|&up| scale(up, 1.0 / norm(up))));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::run::targets;

    /// Takes every command and does nothing with it.
    struct Anywhere;

    impl Controls for Anywhere {
        fn send(&mut self, _: SimCommand) -> Result<(), Stopped> {
            Ok(())
        }
    }

    #[test]
    fn sixteen_verification_orientations_beside_the_calibration_s_are_each_fresh() {
        for seed in 1..=5 {
            let mut hand = SimulatedHand::new(Anywhere, 3.0, seed);
            let calibrated: Vec<[f64; 3]> = targets(false).iter().map(|t| t.up).collect();
            hand.avoid(&calibrated);
            let mut used = calibrated;
            for k in 1..=16 {
                hand.fresh(k, &mut crate::run::Silent { yes: true }).unwrap();
                let up = hand.resting.unwrap();
                let nearest =
                    used.iter().map(|u| shared::orientation::angle_between_deg(up, *u)).fold(f64::MAX, f64::min);
                // NOTE: the procedure wants FRESH_DEG; 5 degrees more leave room for the hand's own error.
                assert!(
                    nearest >= FRESH_DEG + 5.0,
                    "seed {seed}, verification {k}: {nearest:.1} degrees from one used"
                );
                used.push(up);
            }
        }
    }
}
