//! A stream session kept on disk: at the stem the command line chose, held by this run, its log
//! beside it as `SESSION.log` unless given; what it holds is the core's (`run::stream::Keeping`,
//! [`super::kept`]: the still periods as captures in g, the verification once made), saved as the
//! core's run hands it over; going on with one (`--resume`):
//! its log is read again and appended to, so the session's every line stays in one log.

use std::path::{Path, PathBuf};

use accelcal_core::run::stream::Keeping;

use crate::error::Error;
use crate::files::lock::Held;
use crate::session::StreamSource;
use crate::session::{stem_file, stem_of, unix_time_s, Session, SessionError, SessionFiles, SessionKind};

/// A stream session being kept.
pub struct Kept {
    /// The session's path without extension.
    pub stem: PathBuf,
    /// The port, the log and what the stream was read as (filled in once read).
    pub source: StreamSource,
    /// Whether it goes on with a session an earlier run kept.
    pub resumed: bool,
    /// The lines its log held before this run (a resumed session's).
    pub logged: String,
    /// When the session began, seconds since the Unix epoch: its captures' time.
    began_unix_s: f64,
    /// The session file, held by this run while it writes it.
    _held: Held,
}

impl Kept {
    /// A new session at `stem` (held), its lines kept in `log`, read from `port`, of the board
    /// `serial` names when given.
    pub fn new(stem: PathBuf, held: Held, port: &str, log: PathBuf, serial: Option<String>) -> Kept {
        let source = StreamSource {
            port: port.to_owned(),
            log,
            dialect: String::new(),
            input_unit: String::new(),
            gyro_unit: None,
            rate_hz: None,
            serial,
        };
        Kept { stem, source, resumed: false, logged: String::new(), began_unix_s: unix_time_s(), _held: held }
    }

    /// The stream session at `path` (held) and the lines its log holds, to go on with on `port`,
    /// with the serial it records or, where it records none, `serial`.
    pub fn resume(path: &Path, held: Held, port: &str, serial: Option<&str>) -> Result<Kept, Error> {
        let stem = stem_of(path);
        let session = Session::load(&stem_file(&stem, "json"))?;
        let Some(source) = session.stream.filter(|_| session.kind == SessionKind::Stream) else {
            return Err(SessionError::NotAStream { path: path.to_owned() }.into());
        };
        let log = source.log.clone();
        let logged = super::read_text(&log).map_err(|source| Error::ReadFile { path: log, source })?;
        let serial = match (source.serial.clone(), serial) {
            (Some(kept), Some(given)) if kept != given => {
                return Err(
                    SessionError::OtherBoard { path: path.to_owned(), session: kept, board: given.into() }.into()
                )
            }
            (kept, given) => kept.or(given.map(str::to_owned)),
        };
        let source = StreamSource { port: port.to_owned(), serial, ..source };
        Ok(Kept { stem, source, resumed: true, logged, began_unix_s: unix_time_s(), _held: held })
    }

    /// The session's JSON file.
    pub fn json(&self) -> PathBuf {
        stem_file(&self.stem, "json")
    }

    /// What the core's stream run keeps of it: its file, its stream and when it began.
    pub fn keeping(&self) -> Keeping {
        Keeping { json: self.json(), source: self.source.clone(), began_unix_s: self.began_unix_s }
    }

    /// Saves `session` (the core's run made it) as this session's files.
    pub fn save(&self, session: &Session) -> Result<(), SessionError> {
        session.save(&self.stem)
    }
}
