//! Why a self-test could not give a verdict: below the procedure and its phases, which both fail with it.

use crate::link::LinkError;
use crate::still::StillError;

/// Why the self-test could not give a verdict.
#[derive(Debug, thiserror::Error)]
pub enum SelfTestError {
    #[error(transparent)]
    Link(#[from] LinkError),
    #[error("the board found no sensor ({0}): check the wiring and run again")]
    NoSensor(String),
    #[error("the board moved during each of {attempts} attempts, so no response could be measured: rest it on a table, keep your hands off it for 5 s, and run again")]
    KeptMoving { attempts: u8 },
    /// Too few samples arrived (a lost link is [`SelfTestError::Link`]).
    #[error(transparent)]
    Stream(StillError),
    #[error("the sensor's configuration registers read {after:02x?} after the self-test, not {before:02x?} as before: unplug the board and plug it in again")]
    NotRestored { before: Vec<u8>, after: Vec<u8> },
}

impl From<StillError> for SelfTestError {
    fn from(error: StillError) -> Self {
        match error {
            StillError::Link(link) => SelfTestError::Link(link),
            other => SelfTestError::Stream(other),
        }
    }
}
