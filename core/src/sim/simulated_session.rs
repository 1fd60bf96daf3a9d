//! One simulated board's default adaptive session, collected as `calibrate --sim` collects it (for
//! `accelcal repeat`, the statistical tests and the web page's board without hardware): no files, no
//! feedback.

use embassy_futures::block_on;
use shared::protocol::DeviceInfo;

use super::board::InProcess;
use super::simulated_hand::{Controls, SimulatedHand};
use crate::limits::SIM_WAIT_LIMIT;
use crate::link::{Link, Transport};
use crate::run::stop_rule::{Noise, StopRule};
use crate::run::{collect_adaptive, targets, AdaptiveOptions, BoardClock, Moves, ProcedureError, Silent, Turning};
use crate::session::{BoardRecord, Session, SessionKind};

/// How the simulated session is taken: the hand's placement error (degrees) and its seed, the
/// target at a fresh orientation (mg).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SimulatedSession {
    pub placement_deg: f64,
    pub hand_seed: u64,
    pub target_mg: f64,
}

/// The simulated board a session is collected on: its link, what it said to hello, the hand's way
/// to it and its own clock.
pub struct SimulatedBoard<'a, T: Transport> {
    pub link: &'a mut Link<T>,
    pub info: &'a DeviceInfo,
    pub controls: Box<dyn Controls>,
    pub clock: BoardClock,
}

impl SimulatedSession {
    /// The session collected on the realistic simulated board of `seed` in this process (the core's
    /// [`InProcess`] board: no thread, no port), as the native command line and the browser both run it.
    pub fn in_process(&self, seed: u64) -> Result<Session, ProcedureError> {
        let transport = InProcess::realistic(seed);
        let (controls, clock) = (Box::new(transport.controls()), transport.clock());
        let mut link = Link::new(transport);
        block_on(async {
            link.delimit().await?;
            let info = link.hello().await?;
            self.collect(SimulatedBoard { link: &mut link, info: &info, controls, clock }).await
        })
    }

    /// Collects the adaptive session on `board`; the session, its board recorded.
    pub async fn collect<T: Transport>(&self, board: SimulatedBoard<'_, T>) -> Result<Session, ProcedureError> {
        let rate_hz = board.info.config.sample_rate_hz;
        let mut hand = SimulatedHand::new(board.controls, self.placement_deg, self.hand_seed);
        let rule = StopRule { target_mg: self.target_mg, noise: Noise::Measured, rate_hz };
        let options = AdaptiveOptions { rule, wait_limit: Some(SIM_WAIT_LIMIT), clock: Some(board.clock) };
        let record = BoardRecord::of(board.info);
        let mut session = Session { board: Some(record), kind: SessionKind::Adaptive, ..Session::default() };
        collect_adaptive(
            board.link,
            Turning { hand: &mut hand, moves: &mut Moves::at(rate_hz) },
            &targets(false),
            &options,
            &mut Silent { yes: true },
            &mut session,
            &mut |_| Ok(()),
        )
        .await?;
        Ok(session)
    }
}
