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

/// How far beyond [`FRESH_DEG`], in degrees, the hand keeps its verification orientations apart,
/// so that its own placement error never makes one look like a repeat.
const FRESH_MARGIN_DEG: f64 = 10.0;
/// Random orientations tried for one clear of those verified before (14 of them fit easily).
const FRESH_TRIES: usize = 1000;

/// The tool's hand on a simulated board.
pub struct SimulatedHand {
    controls: Sender<SimCommand>,
    rng: Xoshiro256PlusPlus,
    placement_deg: f64,
    verified: Vec<[f64; 3]>,
}

impl SimulatedHand {
    /// A hand on the board behind `controls`, off by about `placement_deg` (random axis, normal
    /// angle), repeatable by `seed`.
    pub fn new(controls: Sender<SimCommand>, placement_deg: f64, seed: u64) -> Self {
        let rng = Xoshiro256PlusPlus::seed_from_u64(seed);
        SimulatedHand { controls, rng, placement_deg, verified: Vec::new() }
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
        self.place(up)
    }

    fn fresh(&mut self, _: usize, _: &mut dyn Feedback) -> Result<(), ProcedureError> {
        let up = self.new_orientation();
        self.verified.push(up);
        self.place(up)
    }

    fn avoid(&mut self, orientations: &[[f64; 3]]) {
        self.verified.extend(orientations.iter().map(|&up| scale(up, 1.0 / norm(up))));
    }
}
