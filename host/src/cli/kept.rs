//! The session a calibration run keeps: a new one, written before the first capture, or one begun in
//! an earlier run on the same board at the same setting (`--resume`).

use crate::session::SessionFiles;
use std::path::{Path, PathBuf};

use shared::protocol::DeviceInfo;
use shared::Calibration;

use super::adaptive;
use super::args::CalibrateArgs;
use crate::error::Error;
use crate::files::lock::{self, Held};
use crate::procedure::{self, Feedback};
use crate::session::{stem_file, stem_of, unix_time_s, BoardRecord, Session, SessionError, SessionKind};

/// The session of this run and where it is kept.
pub(super) struct Kept {
    pub(super) session: Session,
    pub(super) path: Option<PathBuf>,
    /// Whether it continues a session begun in an earlier run.
    pub(super) resumed: bool,
    /// The session file held by this run while it writes it (none when nothing is kept).
    pub(super) _held: Option<Held>,
}

/// The session to continue (`--resume`, checked against the board) or a new one, written at once
/// so that an unwritable path fails before the first capture.
pub(super) fn start(
    args: &CalibrateArgs,
    info: &DeviceInfo,
    learned: Option<Calibration>,
    feedback: &mut dyn Feedback,
) -> Result<Kept, Error> {
    let board = BoardRecord::of(info);
    let holder = holder(&format!("board {}", board.serial));
    let kept = match &args.resume {
        Some(path) => {
            let kept = resumed(path, &board, &holder, feedback)?;
            adaptive::resumed_as_begun(args, &kept.session).iter().for_each(|line| feedback.say(line));
            kept
        }
        None => {
            let (path, held) = new_session_path(args, Some(&board.serial), &holder)?.unzip();
            let session = Session { board: Some(board), kind: adaptive::begun_as(args), learned, ..Session::default() };
            Kept { session, path, resumed: false, _held: held }
        }
    };
    if let Some(path) = &kept.path {
        kept.session.save(path)?;
        feedback.say(&format!("the captures are kept in {} as they are taken", stem_file(path, "json").display()));
    }
    Ok(kept)
}

/// A session from an earlier run, on this board at this setting.
fn resumed(path: &Path, board: &BoardRecord, holder: &str, feedback: &mut dyn Feedback) -> Result<Kept, Error> {
    let stem = stem_of(path);
    let json = stem_file(&stem, "json");
    let held = hold(&stem, holder)?;
    let session = Session::load(&json)?;
    recorded_board(&session, &json)?.check_same(board, &json)?;
    let targets = procedure::targets(session.kind == SessionKind::Quick);
    // NOTE: by name: an adaptive session's closing capture repeats its first position.
    let captured = targets.iter().filter(|t| session.has_capture(&t.name)).count();
    feedback.say(&format!("resuming {}: {captured} of {} positions captured", json.display(), targets.len()));
    Ok(Kept { session, path: Some(stem), resumed: true, _held: Some(held) })
}

/// The board a session to resume on an accelcal board was captured on; a stream session (read from
/// a board's own sketch, which no accelcal board goes on with) is named as such, with its port.
fn recorded_board<'a>(session: &'a Session, json: &Path) -> Result<&'a BoardRecord, SessionError> {
    if let Some(stream) = session.stream.as_ref().filter(|_| session.kind == SessionKind::Stream) {
        return Err(SessionError::StreamOnBoard { path: json.to_owned(), port: stream.port.clone() });
    }
    session.board.as_ref().ok_or(SessionError::NoBoard { path: json.to_owned() })
}

/// Where a new session is kept, held by this run: `--session` (a folder gets a session named by
/// the board and the time inside it), or with a real board the current directory; a name given is
/// refused when a session is kept there or another run holds it, a default name takes the next free
/// suffix. `serial` names the board in the default name; `holder` is what a second run is told.
pub(super) fn new_session_path(
    args: &CalibrateArgs,
    serial: Option<&str>,
    holder: &str,
) -> Result<Option<(PathBuf, Held)>, SessionError> {
    let by_default = default_name(serial);
    match &args.session {
        // NOTE: `DIR/` names a folder even before it exists; the session goes inside it.
        Some(given) if given.is_dir() || given.as_os_str().to_string_lossy().ends_with(std::path::MAIN_SEPARATOR) => {
            std::fs::create_dir_all(given).map_err(|source| SessionError::Write { path: given.clone(), source })?;
            first_free(&given.join(by_default), holder).map(Some)
        }
        Some(given) => {
            let stem = stem_of(given);
            let held = hold(&stem, holder)?;
            match stem_file(&stem, "json").exists() {
                true => Err(SessionError::Exists { path: stem_file(&stem, "json") }),
                false => Ok(Some((stem, held))),
            }
        }
        // NOTE: a simulated board in this process is gone after the run: nothing to keep.
        None => args.device.port.as_ref().map(|_| first_free(&by_default, holder)).transpose(),
    }
}

/// A new session's default name: the board (when it has a serial) and the time, so that boards
/// started in the same second get names of their own.
pub(super) fn default_name(serial: Option<&str>) -> PathBuf {
    let board = serial.map(|serial| format!("{serial}-")).unwrap_or_default();
    PathBuf::from(format!("accelcal-session-{board}{}", unix_time_s() as u64))
}

/// `stem`, or the first of `stem-2`, `stem-3` ... that holds no session and no other run holds, held.
pub(super) fn first_free(stem: &Path, holder: &str) -> Result<(PathBuf, Held), SessionError> {
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
pub(super) fn holder(what: &str) -> String {
    format!("pid {}, {what}", std::process::id())
}

/// The session at `stem` held by this run while it writes it; refused, naming the holder, while
/// another run holds it.
pub(super) fn hold(stem: &Path, holder: &str) -> Result<Held, SessionError> {
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
    use crate::cli::args::{Cli, Command};
    use crate::session::StreamSource;
    use clap::Parser;

    fn args(extra: &[&str]) -> CalibrateArgs {
        match Cli::try_parse_from([&["accelcal", "calibrate"][..], extra].concat()).unwrap().command {
            Command::Calibrate(args) => args,
            _ => unreachable!("parsed as calibrate"),
        }
    }

    fn folder(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("accelcal-kept-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn a_session_another_run_holds_is_refused_naming_that_run_before_either_wrote_it() {
        let stem = folder("held").join("z");
        let given = args(&["--sim", "--session", stem.to_str().unwrap()]);
        let (first, _held) = new_session_path(&given, Some("AB12"), "pid 7, board AB12").unwrap().unwrap();
        assert_eq!(first, stem);
        // NOTE: the first run has written nothing yet: only its lock tells the second of it.
        assert!(!stem_file(&stem, "json").exists());
        let error = new_session_path(&given, Some("CD34"), "pid 8, board CD34").unwrap_err().to_string();
        assert!(error.contains("z.json is being written by another run of accelcal (pid 7, board AB12)"), "{error}");
        assert!(error.contains("wait for it to end, or give another --session name"), "{error}");
    }

    #[test]
    fn boards_started_in_the_same_second_get_sessions_of_their_own() {
        let dir = folder("same-second");
        let given = args(&["--sim", "--session", &format!("{}/", dir.display())]);
        let (one, _one) = new_session_path(&given, Some("AB12"), "pid 7, board AB12").unwrap().unwrap();
        let (two, _two) = new_session_path(&given, Some("CD34"), "pid 8, board CD34").unwrap().unwrap();
        let name = |stem: &Path| stem.file_name().unwrap().to_string_lossy().into_owned();
        assert!(name(&one).starts_with("accelcal-session-AB12-"), "{}", name(&one));
        assert!(name(&two).starts_with("accelcal-session-CD34-"), "{}", name(&two));
        // The same board twice in one second (or a stream without a serial): the next suffix.
        let (again, _again) = new_session_path(&given, Some("AB12"), "pid 9, board AB12").unwrap().unwrap();
        assert_eq!(again, PathBuf::from(format!("{}-2", one.display())));
        std::fs::write(stem_file(&again, "json"), "{}").unwrap();
        drop(_again);
        let (third, _third) = first_free(&one, "pid 10, board AB12").unwrap();
        assert_eq!(third, PathBuf::from(format!("{}-3", one.display())), "a kept session's name was reused");
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
