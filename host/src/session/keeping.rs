//! Where a run keeps its session and holds it while it writes it: a new session's name (given, in a
//! folder, or the default one with the next free suffix), the lock that tells a second run who is
//! writing it, and a board's session begun in an earlier run, gone on with (`--resume`).

use std::path::{Path, PathBuf};

use accelcal_core::run::targets;

use super::{stem_file, stem_of, unix_time_s, BoardRecord, Session, SessionError, SessionFiles, SessionKind};
use crate::files::lock::{self, Held};

/// A board's session as this run keeps it.
pub struct KeptSession {
    pub session: Session,
    /// Where it is kept, without extension; none when nothing is kept (a simulated board's own run).
    pub path: Option<PathBuf>,
    /// Whether it continues a session begun in an earlier run.
    pub resumed: bool,
    /// The session file held by this run while it writes it.
    _held: Option<Held>,
}

impl KeptSession {
    /// A new session, kept at `place` (and held) when it is kept at all.
    pub fn new(session: Session, place: Option<(PathBuf, Held)>) -> Self {
        let (path, held) = place.unzip();
        KeptSession { session, path, resumed: false, _held: held }
    }

    /// The session at `path`, begun in an earlier run on `board`, held by `holder`; how many of its
    /// positions it holds, to tell the person.
    pub fn resume(path: &Path, board: &BoardRecord, holder: &str) -> Result<(Self, String), SessionError> {
        let stem = stem_of(path);
        let json = stem_file(&stem, "json");
        let held = hold(&stem, holder)?;
        let session = Session::load(&json)?;
        recorded_board(&session, &json)?.check_same(board, &json)?;
        let targets = targets(session.kind == SessionKind::Quick);
        // NOTE: by name: an adaptive session's closing capture repeats its first position.
        let captured = targets.iter().filter(|t| session.has_capture(&t.name)).count();
        let said = format!("resuming {}: {captured} of {} positions captured", json.display(), targets.len());
        Ok((KeptSession { session, path: Some(stem), resumed: true, _held: Some(held) }, said))
    }
}

/// The board a session to resume on an accelcal board was captured on; a stream session (read from
/// a board's own sketch, which no accelcal board goes on with) is named as such, with its port.
fn recorded_board<'a>(session: &'a Session, json: &Path) -> Result<&'a BoardRecord, SessionError> {
    if let Some(stream) = session.stream.as_ref().filter(|_| session.kind == SessionKind::Stream) {
        return Err(SessionError::StreamOnBoard { path: json.to_owned(), port: stream.port.clone() });
    }
    session.board.as_ref().ok_or(SessionError::NoBoard { path: json.to_owned() })
}

/// Where a new session is kept, held by this run: `given` (a folder gets a session named by the
/// board and the time inside it), else the default name in the current directory when
/// `by_default`; a name given is refused when a session is kept there or another run holds it, a
/// default name takes the next free suffix. `serial` names the board in the default name; `holder`
/// is what a second run is told.
pub fn new_session_path(
    given: Option<&Path>,
    by_default: bool,
    serial: Option<&str>,
    holder: &str,
) -> Result<Option<(PathBuf, Held)>, SessionError> {
    let default = default_name(serial);
    match given {
        // NOTE: `DIR/` names a folder even before it exists; the session goes inside it.
        Some(given) if given.is_dir() || given.as_os_str().to_string_lossy().ends_with(std::path::MAIN_SEPARATOR) => {
            std::fs::create_dir_all(given).map_err(|source| SessionError::Write { path: given.into(), source })?;
            first_free(&given.join(default), holder).map(Some)
        }
        Some(given) => {
            let stem = stem_of(given);
            let held = hold(&stem, holder)?;
            match stem_file(&stem, "json").exists() {
                true => Err(SessionError::Exists { path: stem_file(&stem, "json") }),
                false => Ok(Some((stem, held))),
            }
        }
        None => by_default.then(|| first_free(&default, holder)).transpose(),
    }
}

/// A new session's default name: the board (when it has a serial) and the time, so that boards
/// started in the same second get names of their own.
pub fn default_name(serial: Option<&str>) -> PathBuf {
    let board = serial.map(|serial| format!("{serial}-")).unwrap_or_default();
    PathBuf::from(format!("accelcal-session-{board}{}", unix_time_s() as u64))
}

/// `stem`, or the first of `stem-2`, `stem-3` ... that holds no session and no other run holds, held.
pub fn first_free(stem: &Path, holder: &str) -> Result<(PathBuf, Held), SessionError> {
    let mut last_busy = None;
    for suffix in 1..=SUFFIXES_TRIED {
        let candidate = match suffix {
            1 => stem.to_owned(),
            n => PathBuf::from(format!("{}-{n}", stem.display())),
        };
        match hold(&candidate, holder) {
            Ok(held) if !stem_file(&candidate, "json").exists() => return Ok((candidate, held)),
            Ok(_) => last_busy = Some(SessionError::Exists { path: stem_file(&candidate, "json") }),
            Err(busy @ SessionError::Busy { .. }) => last_busy = Some(busy),
            Err(error) => return Err(error),
        }
    }
    Err(last_busy.unwrap_or(SessionError::Exists { path: stem_file(stem, "json") }))
}

/// How many default names are tried before the last one's refusal is reported.
const SUFFIXES_TRIED: u32 = 100;

/// This run as a second run is told of it: its process id and `what` (the board it calibrates).
pub fn holder(what: &str) -> String {
    format!("pid {}, {what}", std::process::id())
}

/// The session at `stem` held by this run while it writes it; refused, naming the holder, while
/// another run holds it.
pub fn hold(stem: &Path, holder: &str) -> Result<Held, SessionError> {
    let json = stem_file(stem, "json");
    match lock::hold(&json, holder) {
        Ok(Ok(held)) => Ok(held),
        Ok(Err(holder)) => Err(SessionError::Busy { path: json, holder }),
        Err(source) => Err(SessionError::Write { path: lock::lock_file(&json), source }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::session::StreamSource;

    fn folder(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("accelcal-kept-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn a_session_another_run_holds_is_refused_naming_that_run_before_either_wrote_it() {
        let stem = folder("held").join("z");
        let (first, _held) = new_session_path(Some(&stem), false, Some("AB12"), "pid 7, board AB12").unwrap().unwrap();
        assert_eq!(first, stem);
        // NOTE: the first run has written nothing yet: only its lock tells the second of it.
        assert!(!stem_file(&stem, "json").exists());
        let error = new_session_path(Some(&stem), false, Some("CD34"), "pid 8, board CD34").unwrap_err().to_string();
        assert!(error.contains("z.json is being written by another run of accelcal (pid 7, board AB12)"), "{error}");
        assert!(error.contains("wait for it to end, or give another --session name"), "{error}");
    }

    #[test]
    fn boards_started_in_the_same_second_get_sessions_of_their_own() {
        let dir = PathBuf::from(format!("{}/", folder("same-second").display()));
        let new = |serial: &str, holder: &str| new_session_path(Some(&dir), false, Some(serial), holder);
        let (one, _one) = new("AB12", "pid 7, board AB12").unwrap().unwrap();
        let (two, _two) = new("CD34", "pid 8, board CD34").unwrap().unwrap();
        let name = |stem: &Path| stem.file_name().unwrap().to_string_lossy().into_owned();
        assert!(name(&one).starts_with("accelcal-session-AB12-"), "{}", name(&one));
        assert!(name(&two).starts_with("accelcal-session-CD34-"), "{}", name(&two));
        // The same board twice in one second (or a stream without a serial): the next suffix.
        let (again, _again) = new("AB12", "pid 9, board AB12").unwrap().unwrap();
        assert_eq!(again, PathBuf::from(format!("{}-2", one.display())));
        std::fs::write(stem_file(&again, "json"), "{}").unwrap();
        drop(_again);
        let (third, _third) = first_free(&one, "pid 10, board AB12").unwrap();
        assert_eq!(third, PathBuf::from(format!("{}-3", one.display())), "a kept session's name was reused");
    }

    #[test]
    fn without_a_name_given_a_session_is_kept_only_where_it_is_kept_by_default() {
        assert!(new_session_path(None, false, Some("AB12"), "pid 7").unwrap().is_none());
    }

    #[test]
    fn a_stream_session_resumed_on_an_accelcal_board_is_named_with_the_command_that_resumes_it() {
        let stream = StreamSource { port: "/dev/ttyUSB3".into(), ..StreamSource::for_tests(None, None) };
        let session = Session { kind: SessionKind::Stream, stream: Some(stream), ..Session::default() };
        let error = recorded_board(&session, Path::new("s.json")).unwrap_err().to_string();
        assert!(error.contains("s.json is a session of a board's own stream"), "{error}");
        assert!(error.contains("accelcal calibrate --port /dev/ttyUSB3 --resume s.json"), "{error}");
        let error = recorded_board(&Session::default(), Path::new("c.json")).unwrap_err().to_string();
        assert!(error.contains("c.json records no board"), "{error}");
    }
}
