//! A calibration from a board that prints its own stream, free of I/O: nothing is written to the
//! board; its lines are listened to until the session is done ([`listen`]: once a second the person
//! told where things stand, the session kept on each new still period, the run ended once every
//! face and corner is rested and enough fresh orientations are held, or cut short by a stream
//! that stops, goes away, is unreadable or is refused, or by Ctrl-C), then its kept log fitted
//! as `accelcal fit LOG` fits it ([`finish`]: what is kept, whether it certifies, what to print).
//! The host gives the port's bytes, the time and Ctrl-C (a [`StreamPort`]), keeps the log and the
//! session's files, and certifies what [`Finished`] says certifies.

mod finish;
mod listen;

use std::fmt::Display;
use std::path::PathBuf;

pub use finish::{finish, Finished, StreamRunError};
pub use listen::Listening;

use crate::session::{Session, SessionError, StreamSource, Verification};
use crate::stream::kept;
use crate::stream::{StillPeriods, StreamLog, StreamOptions};

/// What a calibration from a board's own stream is asked.
#[derive(Debug, Clone, PartialEq)]
pub struct CalibrateOptions {
    /// How the stream's lines are read (units, rate).
    pub stream: StreamOptions,
    /// The port's baud rate, named when nothing readable comes.
    pub baud: u32,
    /// The | |a| - g | wanted, in mg: each position is held until its mean is known to what it needs.
    pub target_mg: f64,
    /// Fresh orientations to hold to verify the fit.
    pub verify: usize,
    /// The lot the certificate goes into, when one is given (named in the command that resumes).
    pub lot: Option<PathBuf>,
    /// The report as JSON rather than text.
    pub json: bool,
}

/// What a stream run needs of the host: the bytes the port sends (each kept in the log before it is
/// handed over), the time, and whether the person asked to stop.
// NOTE: async, as the board's `Transport` is: a host whose port answers later (a browser) drives
// the same run as one that blocks (the command line, whose futures are ready at once).
#[allow(async_fn_in_trait)]
pub trait StreamPort {
    /// Why the port could not be read (it went away, or its log could not be written).
    type Error: Display;
    /// What the port sent into `buffer`, waiting a short while at most: the count, 0 when nothing
    /// came.
    async fn read(&mut self, buffer: &mut [u8]) -> Result<usize, Self::Error>;
    /// The host's time, in seconds since listening began.
    fn now_s(&self) -> f64;
    /// Whether the person asked to stop (Ctrl-C).
    fn interrupted(&self) -> bool;
}

/// Where the host keeps a stream run's session: the closure given the session to save.
pub type Keep<'a> = &'a mut dyn FnMut(&Session) -> Result<(), SessionError>;

/// The session a stream run keeps: its file, the stream it records and when it began.
#[derive(Debug, Clone, PartialEq)]
pub struct Keeping {
    /// The session's JSON file, as the person is told (and the command that resumes names it).
    pub json: PathBuf,
    /// The port, the log and the board's serial it records.
    pub source: StreamSource,
    /// When the session began, seconds since the Unix epoch: its captures' time.
    pub began_unix_s: f64,
}

impl Keeping {
    /// The session of `log` so far: its training still periods as captures, and the verification
    /// once made.
    pub fn session(&self, log: &StreamLog, verification: Option<Verification>) -> Session {
        kept::session(log, &StillPeriods::of(log), &self.source, self.began_unix_s, verification)
    }

    /// The command that goes on with the session, with the lot it was to go into.
    pub fn resume_command(&self, options: &CalibrateOptions) -> String {
        let lot = options.lot.as_ref().map(|lot| format!(" --lot {}", lot.display())).unwrap_or_default();
        format!("accelcal calibrate --port {} --resume {}{lot}", self.source.port, self.json.display())
    }
}

#[cfg(test)]
mod tests;
