//! Several boards' sessions run together on one fixture (`calibrate --ports`, `--all-boards`,
//! `--sim --boards N`): each board's session in its own thread, its lines on stderr named by the
//! board, its session file named by its serial; a board that fails is named and the others go on.
//! Where the sessions meet (the hand's turns) is [`super::Fixture`]'s.

use std::fmt::Display;
use std::path::{Path, PathBuf};

use super::Feedback;
use crate::report::fixture::{BoardEnd, FixtureBoard, FixtureReport};
use crate::report::CalibrateReport;
use crate::session::SessionError;

/// Why a board's session has no outcome: its thread ended on a panic.
#[derive(Debug, thiserror::Error)]
#[error(
    "a board's session stopped on an internal fault; its captures so far are in its session file: calibrate it again"
)]
pub struct BoardThreadFailed;

/// Runs `session` for each board (named by its serial, or the port it could not be opened on) in
/// its own thread, its lines on stderr named by the board (none when `quiet`); what became of
/// each, in the fixture's order.
pub fn run_together<B: Send, E: Display>(
    boards: Vec<(String, B)>,
    quiet: bool,
    session: impl Fn(B, &mut dyn Feedback) -> Result<Option<CalibrateReport>, E> + Sync,
) -> FixtureReport {
    let session = &session;
    std::thread::scope(|scope| {
        let running: Vec<_> = boards
            .into_iter()
            .map(|(name, board)| {
                let mut lines = BoardLines { name: name.clone(), quiet };
                (name, scope.spawn(move || BoardEnd::of(session(board, &mut lines))))
            })
            .collect();
        let ended = running.into_iter().map(|(serial, thread)| {
            let end = thread.join().unwrap_or_else(|_| BoardEnd::Failed(BoardThreadFailed.to_string()));
            FixtureBoard { serial, end }
        });
        FixtureReport { boards: ended.collect() }
    })
}

/// Whether `--session` names a folder (it exists as one, or ends with a separator).
fn is_folder(given: &Path) -> bool {
    given.is_dir() || given.as_os_str().to_string_lossy().ends_with(std::path::MAIN_SEPARATOR)
}

/// Makes the folder that `given` (`--session`) names, when it names one.
pub fn make_session_folder(given: Option<&Path>) -> Result<(), SessionError> {
    if let Some(folder) = given.filter(|given| is_folder(given)) {
        std::fs::create_dir_all(folder).map_err(|source| SessionError::Write { path: folder.to_owned(), source })?;
    }
    Ok(())
}

/// Where board `serial`'s session is kept, the fixture's run started at `started_s` (Unix seconds):
/// `given` (`--session`) NAME as NAME-SERIAL, a folder's accelcal-session-TIME-SERIAL inside it,
/// and by default a real board's (`on_port`) in the current directory (none for a simulated one).
pub fn session_path(given: Option<&Path>, serial: &str, started_s: u64, on_port: bool) -> Option<PathBuf> {
    let named = format!("accelcal-session-{started_s}-{serial}");
    match given {
        Some(given) if is_folder(given) => Some(given.join(named)),
        Some(given) => Some(PathBuf::from(format!("{}-{serial}", given.display()))),
        None => on_port.then(|| PathBuf::from(named)),
    }
}

/// A board's lines on stderr, each opened by the board's name; no live line or progress bar (several
/// boards would overwrite each other's).
struct BoardLines {
    name: String,
    quiet: bool,
}

impl Feedback for BoardLines {
    fn say(&mut self, line: &str) {
        if !self.quiet {
            eprintln!("{}: {line}", self.name);
        }
    }
    fn live(&mut self, _: &str) {}
    fn progress(&mut self, _: u32, _: u32) {}
    fn progress_done(&mut self) {}
    fn confirm(&mut self, _: &str) -> bool {
        // NOTE: a fixture runs only with --yes (refused before it starts otherwise).
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_board_runs_in_its_own_thread_and_one_that_fails_or_panics_is_named_in_its_place() {
        let boards = vec![("AA".to_owned(), 1), ("BB".to_owned(), 2), ("CC".to_owned(), 3)];
        let report = run_together(boards, true, |board: i32, feedback| {
            feedback.say("ignored when quiet");
            match board {
                1 => Ok(None),
                2 => Err(format!("board {board} failed")),
                _ => panic!("a fault in board {board}'s session"),
            }
        });
        let serials: Vec<&str> = report.boards.iter().map(|b| b.serial.as_str()).collect();
        assert_eq!(serials, ["AA", "BB", "CC"], "in the fixture's order");
        let ends: Vec<&BoardEnd> = report.boards.iter().map(|b| &b.end).collect();
        assert!(matches!(ends[0], BoardEnd::NotUploaded), "{:?}", ends[0]);
        assert!(matches!(ends[1], BoardEnd::Failed(why) if why == "board 2 failed"), "{:?}", ends[1]);
        assert!(matches!(ends[2], BoardEnd::Failed(why) if why.contains("internal fault")), "{:?}", ends[2]);
    }

    #[test]
    fn a_boards_session_is_named_by_its_serial_beside_or_inside_what_session_names() {
        let sep = std::path::MAIN_SEPARATOR;
        let folder = std::env::temp_dir().join(format!("accelcal-together-{}{sep}", std::process::id()));
        let inside = session_path(Some(&folder), "AB12", 1700, false).unwrap();
        assert_eq!(inside, folder.join("accelcal-session-1700-AB12"));
        let named = session_path(Some(Path::new("batch/run")), "AB12", 1700, true).unwrap();
        assert_eq!(named, PathBuf::from("batch/run-AB12"));
        assert_eq!(session_path(None, "AB12", 1700, true), Some(PathBuf::from("accelcal-session-1700-AB12")));
        assert_eq!(session_path(None, "AB12", 1700, false), None, "a simulated board keeps no session unasked");
        make_session_folder(Some(&folder)).unwrap();
        assert!(folder.is_dir());
        std::fs::remove_dir(&folder).unwrap();
    }
}
