//! A stream session kept on disk: where it goes (`--session`, default `accelcal-session-TIME`,
//! its log beside it as `SESSION.log` unless `--stream-log`), what it holds (the still periods as
//! captures in g, the verification once made), and going on with one (`--resume`: its log is
//! read again and appended to, so the session's every line stays in one log).

use crate::session::SessionFiles;
use std::path::{Path, PathBuf};

use super::args::CalibrateArgs;
use super::kept::{default_name, first_free, hold, holder, new_session_path};
use crate::error::Error;
use crate::files::lock::Held;
use crate::session::{stem_file, stem_of, unix_time_s, Session, SessionError, SessionKind};
use crate::session::{StreamSource, Verification};
use crate::stream::{kept, StillPeriods, StreamLog};

/// A stream session being kept.
pub(super) struct Kept {
    /// The session's path without extension.
    pub stem: PathBuf,
    /// The port, the log and what the stream was read as (filled in once read).
    pub source: StreamSource,
    /// When the session began, seconds since the Unix epoch: its captures' time.
    began_unix_s: f64,
    /// The session file, held by this run while it writes it.
    _held: Held,
}

impl Kept {
    /// A new session, or the one `--resume` names with the lines its log already holds.
    pub fn begin(args: &CalibrateArgs, port: &str) -> Result<(Kept, String), Error> {
        let serial = args.serial.as_deref();
        let holder = holder(&serial.map_or_else(|| format!("port {port}"), |serial| format!("board {serial}")));
        if let Some(path) = &args.resume {
            return resume(path, port, serial, &holder);
        }
        let (stem, held) = match new_session_path(args, serial, &holder)? {
            Some(new) => new,
            None => first_free(&default_name(serial), &holder)?,
        };
        let log = args.stream_log.clone().unwrap_or_else(|| stem_file(&stem, "log"));
        // NOTE: a new session's log holds its lines alone: appended to another's, it would be fitted
        // with that session's lines too.
        args.replace.check(&log, "give another --stream-log, or go on with the session it keeps with --resume")?;
        let source = StreamSource {
            port: port.to_owned(),
            log,
            dialect: String::new(),
            input_unit: String::new(),
            gyro_unit: None,
            rate_hz: None,
            serial: args.serial.clone(),
        };
        Ok((Kept { stem, source, began_unix_s: unix_time_s(), _held: held }, String::new()))
    }

    /// The session's JSON file.
    pub fn json(&self) -> PathBuf {
        stem_file(&self.stem, "json")
    }

    /// Saves the session of `log` so far: its training still periods as captures, and the
    /// verification once made; the session saved.
    pub fn save(&self, log: &StreamLog, verification: Option<Verification>) -> Result<Session, SessionError> {
        let session = kept::session(log, &StillPeriods::of(log), &self.source, self.began_unix_s, verification);
        session.save(&self.stem)?;
        Ok(session)
    }
}

/// The stream session at `path` and the lines its log holds, to go on with on `port`, with the
/// serial it records or, where it records none, `serial`.
fn resume(path: &Path, port: &str, serial: Option<&str>, holder: &str) -> Result<(Kept, String), Error> {
    let stem = stem_of(path);
    let held = hold(&stem, holder)?;
    let session = Session::load(&stem_file(&stem, "json"))?;
    let Some(source) = session.stream.filter(|_| session.kind == SessionKind::Stream) else {
        return Err(SessionError::NotAStream { path: path.to_owned() }.into());
    };
    let log = source.log.clone();
    let before = crate::stream::read_text(&log).map_err(|source| Error::ReadFile { path: log, source })?;
    let serial = match (source.serial.clone(), serial) {
        (Some(kept), Some(given)) if kept != given => {
            return Err(SessionError::OtherBoard { path: path.to_owned(), session: kept, board: given.into() }.into())
        }
        (kept, given) => kept.or(given.map(str::to_owned)),
    };
    let source = StreamSource { port: port.to_owned(), serial, ..source };
    Ok((Kept { stem, source, began_unix_s: unix_time_s(), _held: held }, before))
}
