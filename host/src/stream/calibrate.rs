//! Calibrating from a board that prints its own stream: the core's stream run
//! (`accelcal_core::run::stream`: listened to until done, its log fitted, what to print) on a port
//! read with this process's clock and Ctrl-C ([`LiveStream`]), its log and its session kept on disk
//! ([`Kept`]), and its certificate issued through the step it is given when the run certifies.

use std::path::Path;
use std::sync::atomic::AtomicBool;

pub use accelcal_core::run::stream::CalibrateOptions;
use accelcal_core::run::stream::{finish, Listening, StreamRunError};
use embassy_futures::block_on;

use super::live::LiveStream;
use super::session::Kept;
use crate::error::Error;
use crate::link::TalkingPort;
use crate::procedure::Feedback;
use crate::session::Session;

/// What is done with a complete session's certificate: issued beside the session and added to the
/// lot, or withheld, said why.
pub type Certify<'a> = &'a mut dyn FnMut(&Session, &mut dyn Feedback) -> Result<(), Error>;

/// Calibrates from the stream of `talking`, keeping the session in `kept`, until done or Ctrl-C
/// (`interrupt`); what to print: the report and where the session and the log are kept.
pub fn calibrate(
    talking: TalkingPort,
    kept: &Kept,
    options: &CalibrateOptions,
    interrupt: &AtomicBool,
    feedback: &mut dyn Feedback,
    certify: Certify,
) -> Result<String, Error> {
    if options.lot.is_some() && kept.source.serial.is_none() {
        return Err(Error::StreamLotNeedsSerial { port: talking.path });
    }
    let log = kept.source.log.clone();
    let unwritable = |source| Error::WriteFile { path: log.clone(), source };
    let file = open_log(&log, kept.resumed).map_err(unwritable)?;
    feedback.say(&begun(&talking, kept));
    let (keeping, mut keep) = (kept.keeping(), |session: &Session| kept.save(session));
    let mut listening = Listening::new(options, &kept.logged, &talking.heard);
    let mut live = LiveStream::new(talking, file, interrupt).map_err(unwritable)?;
    let ended = block_on(listening.until_done(&mut live, &keeping, feedback, &mut keep))?;
    live.finish(&listening.closing()).map_err(unwritable)?;
    let text = super::read_text(&log).map_err(|source| Error::ReadFile { path: log.clone(), source })?;
    let finished = finish(&text, &ended, options, &keeping, feedback, &mut keep).map_err(|e| not_fitted(e, &log))?;
    if finished.certifies {
        certify(&finished.session, feedback)?;
    }
    Ok(finished.printed)
}

/// What the person is told as the stream is taken: the port, that nothing is written to it, and
/// where its lines and its session are kept.
fn begun(talking: &TalkingPort, kept: &Kept) -> String {
    let late = match talking.greeted {
        true => ", begun only after accelcal's hello (a board the port's opening reset, or a slow sketch); accelcal writes nothing more to it",
        false => ": accelcal writes nothing to it",
    };
    format!(
        "{} prints its own stream{late} and keeps what it prints in {} (the session in {})",
        talking.path,
        kept.source.log.display(),
        kept.json().display()
    )
}

/// The session's log: a resumed session's goes on, a new one's starts empty (one already there was
/// refused unless --overwrite).
fn open_log(log: &Path, resumed: bool) -> std::io::Result<std::fs::File> {
    let mut options = std::fs::OpenOptions::new();
    match resumed {
        true => options.create(true).append(true),
        false => options.create(true).write(true).truncate(true),
    };
    options.open(log)
}

/// The run's end as the command line's error, naming the log.
fn not_fitted(error: StreamRunError, log: &Path) -> Error {
    match error {
        StreamRunError::Kept(e) => e.into(),
        StreamRunError::Log(source) => Error::Stream { path: log.to_owned(), source },
        StreamRunError::Fit(source) => Error::StreamFit { path: log.to_owned(), source },
    }
}
