//! The tool's own hand on the simulated board: it turns the board through the board's controls
//! handle to each wanted orientation, a few degrees off at random as a person's hand would, and to
//! random orientations for verification.

use std::sync::mpsc::Sender;

use rand_xoshiro::rand_core::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;
use shared::linalg::{add, cross, norm, scale};

use super::{Feedback, Hand, Orientation, ProcedureError};
use crate::limits::FRESH_DEG;
use crate::sim::random::{gaussian, random_unit};
use crate::sim::SimCommand;
use firmware::sim::physics::Motion;

/// How far beyond [`FRESH_DEG`], in degrees, the hand keeps its verification orientations apart,
/// so that its own placement error never makes one look like a repeat.
const FRESH_MARGIN_DEG: f64 = 10.0;
/// Random orientations tried for one clear of those verified before (14 of them fit easily).
const FRESH_TRIES: usize = 1000;
/// How long a person takes to turn the board to a new orientation and let it settle, in seconds.
// NOTE: the estimate (1.5-2 s); the procedure's own stillness check (two half-second windows)
// comes on top.
pub const PERSON_TURN_SECONDS: f64 = 1.5;
/// A turn of this many degrees or more takes the whole turn time; smaller ones proportionally less.
const FULL_TURN_DEG: f64 = 45.0;

/// The tool's hand on a simulated board.
pub struct SimulatedHand {
    controls: Sender<SimCommand>,
    rng: Xoshiro256PlusPlus,
    placement_deg: f64,
    verified: Vec<[f64; 3]>,
    /// Where up pointed when the hand last put the board down.
    last_up: [f64; 3],
    /// Seconds a turn takes (0: the board is put down at once).
    turn_seconds: f64,
}

impl SimulatedHand {
    /// A hand on the board behind `controls`, off by about `placement_deg` (random axis, normal
    /// angle), repeatable by `seed`.
    pub fn new(controls: Sender<SimCommand>, placement_deg: f64, seed: u64) -> Self {
        let rng = Xoshiro256PlusPlus::seed_from_u64(seed);
        SimulatedHand {
            controls,
            rng,
            placement_deg,
            verified: Vec::new(),
            last_up: [0.0, 0.0, 1.0],
            turn_seconds: 0.0,
        }
    }

    /// The hand turning the board over `seconds` of the board's time (a steady turn from where it
    /// rests), as a person does, instead of putting it down at once.
    pub fn turning(self, seconds: f64) -> Self {
        SimulatedHand { turn_seconds: seconds, ..self }
    }

    /// Moves the board to rest with `up` pointing up: at once, or by a steady turn.
    fn turn(&mut self, up: [f64; 3]) -> Result<(), ProcedureError> {
        let from = std::mem::replace(&mut self.last_up, up);
        let angle_deg = shared::orientation::angle_between_deg(from, up);
        if self.turn_seconds <= 0.0 || angle_deg < 1e-3 {
            return self.place(up);
        }
        // The board turns about up x from: gravity turns back about it, from `from` to `up`.
        let mut axis = cross(up, from);
        if norm(axis) < 1e-9 {
            axis = cross(from, random_unit(&mut self.rng));
        }
        let axis = scale(axis, 1.0 / norm(axis)).map(|v| v as f32);
        // NOTE: a small correction is quick; a turn to another position (45 degrees or more) takes
        // the whole time. A slow creep would pass the stillness windows and spoil the capture.
        let seconds = self.turn_seconds * (angle_deg / FULL_TURN_DEG).min(1.0);
        let motion = Motion::Rotating { axis, rate_dps: (angle_deg / seconds) as f32 };
        self.place(from)?;
        let command = SimCommand::MoveFor { motion, seconds: seconds as f32 };
        self.controls.send(command).map_err(|_| ProcedureError::SimulatedBoardStopped)
    }

    fn place(&mut self, up: [f64; 3]) -> Result<(), ProcedureError> {
        let command = SimCommand::Place(up.map(|v| v as f32));
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
    /// somewhere new; the procedure insists on it).
    fn new_orientation(&mut self) -> [f64; 3] {
        let clear = |up: [f64; 3], verified: &[[f64; 3]]| {
            verified.iter().all(|v| shared::orientation::angle_between_deg(up, *v) >= FRESH_DEG + FRESH_MARGIN_DEG)
        };
        let mut up = random_unit(&mut self.rng);
        for _ in 0..FRESH_TRIES {
            if clear(up, &self.verified) {
                break;
            }
            up = random_unit(&mut self.rng);
        }
        up
    }
}

impl Hand for SimulatedHand {
    fn present(&mut self, target: &Orientation, _: &mut dyn Feedback) -> Result<(), ProcedureError> {
        let up = self.misplaced(target.up);
        self.turn(up)
    }

    fn fresh(&mut self, _: usize, _: &mut dyn Feedback) -> Result<(), ProcedureError> {
        let up = self.new_orientation();
        self.verified.push(up);
        self.turn(up)
    }

    fn avoid(&mut self, orientations: &[[f64; 3]]) {
        self.verified.extend(orientations.iter().map(|&up| scale(up, 1.0 / norm(up))));
    }
}
