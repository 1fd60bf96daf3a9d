//! One simulated board's default adaptive session, collected in this process as `calibrate --sim`
//! collects it (for `accelcal repeat` and the statistical tests): no files, no feedback.

use std::sync::Arc;

use super::stop_rule::{Noise, StopRule};
use super::{collect_adaptive, targets, AdaptiveOptions, Moves, ProcedureError, Silent, SimulatedHand, Turning};
use crate::limits::SIM_WAIT_LIMIT;
use crate::link::Connection;
use crate::session::{BoardRecord, Session, SessionKind};
use crate::sim::SimBoard;

/// How the simulated session is taken: the hand's placement error (degrees) and its seed, the
/// target at a fresh orientation (mg).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SimulatedSession {
    pub placement_deg: f64,
    pub hand_seed: u64,
    pub target_mg: f64,
}

impl SimulatedSession {
    /// Collects the adaptive session on `board` over `connection`; the session, its board recorded.
    pub fn collect(&self, connection: &mut Connection, board: &SimBoard) -> Result<Session, ProcedureError> {
        let rate_hz = connection.info.config.sample_rate_hz;
        let mut hand = SimulatedHand::new(board.controls(), self.placement_deg, self.hand_seed);
        let rule = StopRule { target_mg: self.target_mg, noise: Noise::Measured, rate_hz };
        let options = AdaptiveOptions { rule, wait_limit: Some(SIM_WAIT_LIMIT), clock: Some(Arc::new(board.clock())) };
        let record = BoardRecord::of(&connection.info);
        let mut session = Session { board: Some(record), kind: SessionKind::Adaptive, ..Session::default() };
        collect_adaptive(
            &mut connection.client,
            Turning { hand: &mut hand, moves: &mut Moves::at(rate_hz) },
            &targets(false),
            &options,
            &mut Silent { yes: true },
            &mut session,
            &mut |_| Ok(()),
        )?;
        Ok(session)
    }
}
