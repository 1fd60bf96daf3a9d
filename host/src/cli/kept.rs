//! The session a calibration run keeps: a new one, written before the first capture, or one begun in
//! an earlier run on the same board at the same setting (`--resume`).

use crate::session::SessionFiles;
use std::path::{Path, PathBuf};

use shared::protocol::DeviceInfo;
use shared::Calibration;

use super::adaptive;
use super::args::CalibrateArgs;
use crate::error::Error;
use crate::procedure::{self, Feedback};
use crate::session::{stem_file, stem_of, unix_time_s, BoardRecord, Session, SessionError, SessionKind};

/// The session of this run and where it is kept.
pub(super) struct Kept {
    pub(super) session: Session,
    pub(super) path: Option<PathBuf>,
    /// Whether it continues a session begun in an earlier run.
    pub(super) resumed: bool,
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
    let kept = match &args.resume {
        Some(path) => {
            let kept = resumed(path, &board, feedback)?;
            adaptive::resumed_as_begun(args, &kept.session).iter().for_each(|line| feedback.say(line));
            kept
        }
        None => Kept {
            session: Session { board: Some(board), kind: adaptive::begun_as(args), learned, ..Session::default() },
            path: new_session_path(args)?,
            resumed: false,
        },
    };
    if let Some(path) = &kept.path {
        kept.session.save(path)?;
        feedback.say(&format!("the captures are kept in {} as they are taken", stem_file(path, "json").display()));
    }
    Ok(kept)
}

/// A session from an earlier run, on this board at this setting.
fn resumed(path: &Path, board: &BoardRecord, feedback: &mut dyn Feedback) -> Result<Kept, Error> {
    let stem = stem_of(path);
    let json = stem_file(&stem, "json");
    let session = Session::load(&json)?;
    recorded_board(&session, &json)?.check_same(board, &json)?;
    let targets = procedure::targets(session.kind == SessionKind::Quick);
    // NOTE: by name: an adaptive session's closing capture repeats its first position.
    let captured = targets.iter().filter(|t| session.has_capture(&t.name)).count();
    feedback.say(&format!("resuming {}: {captured} of {} positions captured", json.display(), targets.len()));
    Ok(Kept { session, path: Some(stem), resumed: true })
}

/// The board a session to resume on an accelcal board was captured on; a stream session (read from
/// a board's own sketch, which no accelcal board goes on with) is named as such, with its port.
fn recorded_board<'a>(session: &'a Session, json: &Path) -> Result<&'a BoardRecord, SessionError> {
    if let Some(stream) = session.stream.as_ref().filter(|_| session.kind == SessionKind::Stream) {
        return Err(SessionError::StreamOnBoard { path: json.to_owned(), port: stream.port.clone() });
    }
    session.board.as_ref().ok_or(SessionError::NoBoard { path: json.to_owned() })
}

/// Where a new session is kept: `--session` (a folder gets a session named by the time inside it),
/// or with a real board the current directory; refused when a session is already kept there.
pub(super) fn new_session_path(args: &CalibrateArgs) -> Result<Option<PathBuf>, SessionError> {
    let named_by_time = || PathBuf::from(format!("accelcal-session-{}", unix_time_s() as u64));
    let path = match &args.session {
        // NOTE: `DIR/` names a folder even before it exists; the session goes inside it.
        Some(given) if given.is_dir() || given.as_os_str().to_string_lossy().ends_with(std::path::MAIN_SEPARATOR) => {
            std::fs::create_dir_all(given).map_err(|source| SessionError::Write { path: given.clone(), source })?;
            Some(given.join(named_by_time()))
        }
        Some(given) => Some(stem_of(given)),
        // NOTE: a simulated board in this process is gone after the run: nothing to keep.
        None => args.device.port.as_ref().map(|_| named_by_time()),
    };
    match path {
        Some(stem) if stem_file(&stem, "json").exists() => Err(SessionError::Exists { path: stem_file(&stem, "json") }),
        path => Ok(path),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::session::StreamSource;

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
