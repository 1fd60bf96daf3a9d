//! The simulated board a Web Worker serves behind the page's simulated port (web/page/sim-worker.js):
//! the core's board in this process (the firmware's serve step on the realistic simulated MPU-6050,
//! in lockstep with the reads, as `calibrate --sim` runs it) and the tool's own hand on it, which
//! follows the page's prompts with the placement errors `calibrate --sim --seed SEED` draws.

use accelcal_core::link::Transport;
use accelcal_core::run::{Hand, Orientation, Silent};
use accelcal_core::sim::{InProcess, SimulatedHand};
use embassy_futures::block_on;
use wasm_bindgen::prelude::*;

/// The hand's placement error, in degrees: `calibrate --sim`'s default (`--sim-placement-deg`).
const PLACEMENT_DEG: f64 = crate::PLACEMENT_DEG;
/// The most bytes one read hands over: more than one step of the board writes.
const READ_BYTES: usize = 64 * 1024;

/// A simulated board and the hand on it.
#[wasm_bindgen]
pub struct SimulatedBoard {
    board: InProcess,
    seed: u64,
    hand: Option<SimulatedHand>,
}

#[wasm_bindgen]
impl SimulatedBoard {
    /// The realistic simulated board of `seed` (its noise, its serial number and its hand's draws),
    /// just powered on.
    #[wasm_bindgen(constructor)]
    pub fn new(seed: u64) -> SimulatedBoard {
        SimulatedBoard { board: InProcess::realistic(seed), seed, hand: None }
    }

    /// Hands what the page wrote to the board.
    pub fn write(&mut self, bytes: &[u8]) {
        // NOTE: the in-process board's write takes the bytes at once and cannot fail.
        let _ = block_on(self.board.write(bytes));
    }

    /// What the board wrote since: one step of the board when nothing was left to read (lockstep).
    pub fn read(&mut self) -> Vec<u8> {
        let mut buffer = vec![0; READ_BYTES];
        let n = block_on(self.board.read(&mut buffer)).unwrap_or(0);
        buffer.truncate(n);
        buffer
    }

    /// The board's own time since power-on, in seconds.
    #[wasm_bindgen(js_name = boardSeconds)]
    pub fn board_seconds(&self) -> f64 {
        (self.board.clock())()
    }

    /// A new hand takes the board, as `calibrate --sim` gives one to the captures and one to the
    /// verification, each seeded by the board's seed.
    #[wasm_bindgen(js_name = newHand)]
    pub fn new_hand(&mut self) {
        self.hand = Some(SimulatedHand::new(self.board.controls(), PLACEMENT_DEG, self.seed));
    }

    /// The hand rests the board with `up` (three numbers) up, a few degrees off.
    pub fn present(&mut self, name: String, up: &[f64]) -> Result<(), JsError> {
        let up = three(up)?;
        let target = Orientation { name, up, tolerance_deg: 0.0 };
        self.with_hand(|hand| hand.present(&target, &mut Silent { yes: true }))
    }

    /// The hand turns the board to a fresh orientation for verification `index`.
    pub fn fresh(&mut self, index: u32) -> Result<(), JsError> {
        self.with_hand(|hand| hand.fresh(index as usize, &mut Silent { yes: true }))
    }

    /// The hand turns the board a quarter turn over an edge.
    #[wasm_bindgen(js_name = turnQuarter)]
    pub fn turn_quarter(&mut self) -> Result<(), JsError> {
        self.with_hand(|hand| hand.turn_quarter(&mut Silent { yes: true }))
    }

    /// Orientations (three numbers each) the hand's fresh ones keep away from.
    pub fn avoid(&mut self, ups: &[f64]) -> Result<(), JsError> {
        let ups: Vec<[f64; 3]> = ups.chunks(3).map(three).collect::<Result<_, _>>()?;
        self.with_hand(|hand| {
            hand.avoid(&ups);
            Ok(())
        })
    }

    fn with_hand(
        &mut self,
        act: impl FnOnce(&mut SimulatedHand) -> Result<(), accelcal_core::run::ProcedureError>,
    ) -> Result<(), JsError> {
        let hand =
            self.hand.as_mut().ok_or_else(|| JsError::new("no hand on the simulated board: call newHand first"))?;
        act(hand).map_err(|e| JsError::new(&e.to_string()))
    }
}

/// Three numbers as a direction.
fn three(numbers: &[f64]) -> Result<[f64; 3], JsError> {
    <[f64; 3]>::try_from(numbers)
        .map_err(|_| JsError::new(&format!("a direction has 3 numbers, not {}", numbers.len())))
}
