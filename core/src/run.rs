//! The calibration run: how a session is begun, collected, fitted, uploaded, verified, certified,
//! resumed and interrupted, free of I/O. Its steps are `async` functions over the board's
//! [`Link`](crate::link::Link), which the host gives its bytes and its time through a
//! [`Transport`](crate::link::Transport); the person is a [`Feedback`] (what to tell, what to ask) and
//! a [`Hand`] (who turns the board); what to keep goes to the host's `keep`. One board's run is
//! [`board`]; a calibration from a board that prints its own stream is [`stream`], over the host's
//! [`StreamPort`](stream::StreamPort) rather than a link. The decisions: the
//! order that measures a drift ([`drift`]), how a run ended and whether it certifies ([`ending`]),
//! what a resumed run keeps and claims ([`resume`]), where several boards on one fixture meet
//! ([`fixture`]), when a capture stops ([`stop_rule`]), when the board is where it should be and
//! still ([`wait`]), the moves between captures ([`moves`]).

mod adaptive;
pub mod board;
mod choice;
mod collect;
pub mod drift;
pub mod ending;
mod error;
mod feedback;
pub mod fixture;
mod gyro;
mod gyro_check;
mod hand;
mod moves;
pub mod resume;
pub mod stop_rule;
pub mod stream;
mod turns;
mod verify;
mod wait;
mod wanted;

pub use crate::orientation::{corners, faces, quick_set, Orientation};
pub use crate::session::{TargetVerdict, TurnCheck};
pub use adaptive::{AdaptiveOptions, BoardClock};
pub use choice::{outcome, Fitted};
pub use collect::{collect, collect_adaptive, collect_into, gather, CollectOptions, Collected, Plan};
pub use error::ProcedureError;
pub use feedback::{Feedback, Silent, Told};
pub use fixture::{FixtureHand, MeetingPlace};
pub use gyro_check::check_turn;
pub use hand::{Hand, PersonHand};
pub use moves::{Moves, RecordedMove, Turning};
pub use turns::{fit_moves, turn_summaries, turns_of};
pub use verify::{verify, verify_clear_of, verify_with, Verification, VERIFY_SECONDS};

/// Capture length of a quick calibration, in seconds: the shortest the board takes.
///
/// NOTE: a board just powered on warms, and its offsets drift with it (about 0.03 mg/s, simulated
/// sensor); the shorter session drifts less, and a 5 s mean still carries only 0.13 mg of noise per
/// axis (400 ug/sqrt(Hz), Product Specification 6.2). Measured (tests/quick_mode.rs, 20 seeds):
/// 5 s captures 0.320 mg rms true error, 68 s on the board; 10 s captures 0.454 mg, 118 s (with a hand
/// that put the board down at once; turning at a person's pace, 5 s: 0.361 mg, 82 s).
pub const QUICK_CAPTURE_SECONDS: u8 = shared::protocol::MIN_CAPTURE_SECONDS;

/// The capture length when the user does not choose one, in seconds.
pub fn capture_seconds(quick: bool) -> u8 {
    if quick {
        QUICK_CAPTURE_SECONDS
    } else {
        shared::protocol::DEFAULT_CAPTURE_SECONDS
    }
}

/// The orientations a calibration asks for: the six faces and the eight corners, or for a quick one
/// the ten of [`quick_set`].
pub fn targets(quick: bool) -> Vec<Orientation> {
    if quick {
        quick_set()
    } else {
        [faces(), corners()].concat()
    }
}
