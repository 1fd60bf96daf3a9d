//! `calibrate` with several boards on one fixture (`--ports`, `--all-boards`, `--sim --boards N`):
//! each board runs the one-board session (`calibrate_board`) in its own thread, all turned by one
//! hand (`procedure::Fixture`); a board that fails is named and the others go on.

use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;
use std::sync::Arc;

use serde::Serialize;

use super::args::CalibrateArgs;
use super::calibrate::calibrate_board;
use super::device::Opened;
use super::terminal::interrupt_on_ctrl_c;
use crate::error::Error;
use crate::link::{find_boards, serial_ports};
use crate::procedure::{Feedback, Fixture};
use crate::report::{self, CalibrateReport};
use crate::session::{unix_time_s, BoardRecord, SessionError};
use crate::sim::SimSensor;

/// Whether `calibrate` was given a fixture (several boards, or a list of ports) rather than one board.
pub(super) fn holds_several(args: &CalibrateArgs) -> bool {
    args.fixture.boards > 1 || !args.fixture.ports.is_empty() || args.fixture.all_boards
}

/// A board on the fixture: its name (serial number, or the port it could not be opened on), the
/// arguments its session runs with, and the board opened (or why not).
struct Board {
    name: String,
    args: CalibrateArgs,
    opened: Result<Opened, Error>,
}

/// What became of a board: its report, or why it failed.
struct Outcome {
    name: String,
    result: Result<Option<CalibrateReport>, Error>,
}

/// Calibrates the fixture's boards together and reports each.
pub(super) fn calibrate_together(args: &CalibrateArgs) -> Result<(), Error> {
    if args.resume.is_some() {
        return Err(Error::FixtureCannotResume);
    }
    if !args.yes {
        return Err(Error::FixtureNeedsYes);
    }
    let boards = usize::from(args.fixture.boards);
    if let Some(pull) = args.fixture.sim_pull.filter(|pull| pull.board >= boards) {
        return Err(Error::NoSuchBoard { board: pull.board + 1, boards });
    }
    let mut boards = open_all(args)?;
    let members = boards
        .iter()
        .enumerate()
        .map(|(index, b)| b.opened.as_ref().ok().and_then(|opened| opened.as_member(index, args.fixture.sim_pull)));
    let fixture = Fixture::new(members.collect());
    for (index, board) in boards.iter_mut().enumerate() {
        // NOTE: a board that could not be opened leaves the fixture at once (its seat dropped here).
        let seat = fixture.seat(index);
        if let Ok(opened) = &mut board.opened {
            opened.seat = seat;
        }
    }
    let outcomes = run(boards, interrupt_on_ctrl_c(), args.json && args.device.sim);
    show_all(&outcomes, args.json)
}

/// Every board of the fixture, each with its own arguments; a board that cannot be opened is kept
/// with its cause (the others go on), none at all is an error.
fn open_all(args: &CalibrateArgs) -> Result<Vec<Board>, Error> {
    let started_s = unix_time_s() as u64;
    let devices: Vec<(String, CalibrateArgs)> = if args.device.sim {
        (0..u64::from(args.fixture.boards))
            .map(|k| (format!("simulated board {}", k + 1), simulated(args, k)))
            .collect()
    } else {
        ports_of(args)?.into_iter().map(|port| (port.clone(), on_port(args, port))).collect()
    };
    if let Some(folder) = args.session.as_deref().filter(|given| is_folder(given)) {
        std::fs::create_dir_all(folder).map_err(|source| SessionError::Write { path: folder.to_owned(), source })?;
    }
    Ok(devices.into_iter().map(|(name, board_args)| open_board(name, board_args, started_s)).collect())
}

/// Opens one board and names it by its serial number, its session kept under that name.
fn open_board(name: String, mut args: CalibrateArgs, started_s: u64) -> Board {
    if !args.device.sim {
        // NOTE: each port is listened to (1.2 s) before anything is written to it: say so, it takes seconds.
        eprintln!("{name}: listening, then greeting it if it stays silent");
    }
    let opened = args.device.open();
    let name = match &opened {
        Ok(opened) => BoardRecord::of(&opened.connection.info).serial,
        Err(_) => name,
    };
    args.session = session_of(&args, &name, started_s);
    Board { name, args, opened }
}

/// Simulated board `k` (from 0): its own seed, a part drawn by it unless another sensor was chosen.
fn simulated(args: &CalibrateArgs, k: u64) -> CalibrateArgs {
    let mut board = args.clone();
    board.device.seed = args.device.seed + k;
    board.device.sim_sensor = Some(args.device.sim_sensor.unwrap_or(SimSensor::Drawn));
    board.sim_hand_seed = Some(args.sim_hand_seed.unwrap_or(args.device.seed));
    board
}

/// The board on `port`.
fn on_port(args: &CalibrateArgs, port: String) -> CalibrateArgs {
    let mut board = args.clone();
    board.device.port = Some(port);
    board
}

/// The ports of the fixture: those given, or every accelcal board found.
fn ports_of(args: &CalibrateArgs) -> Result<Vec<String>, Error> {
    if !args.fixture.all_boards {
        return Ok(args.fixture.ports.clone());
    }
    Ok(find_boards(&serial_ports()?, &mut super::device::asking)?)
}

/// Whether `--session` names a folder (it exists as one, or ends with a separator).
fn is_folder(given: &Path) -> bool {
    given.is_dir() || given.as_os_str().to_string_lossy().ends_with(std::path::MAIN_SEPARATOR)
}

/// Where board `serial`'s session is kept: `--session NAME` as NAME-SERIAL, a folder's
/// accelcal-session-TIME-SERIAL inside it, and by default (a real board) in the current directory.
fn session_of(args: &CalibrateArgs, serial: &str, started_s: u64) -> Option<PathBuf> {
    let named = format!("accelcal-session-{started_s}-{serial}");
    match &args.session {
        Some(given) if is_folder(given) => Some(given.join(named)),
        Some(given) => Some(PathBuf::from(format!("{}-{serial}", given.display()))),
        None => args.device.port.as_ref().map(|_| PathBuf::from(named)),
    }
}

/// Runs every board's session in its own thread; what became of each, in the fixture's order.
fn run(boards: Vec<Board>, interrupt: Arc<AtomicBool>, quiet: bool) -> Vec<Outcome> {
    std::thread::scope(|scope| {
        let running: Vec<_> = boards
            .into_iter()
            .map(|board| {
                let (name, interrupt) = (board.name.clone(), interrupt.clone());
                (name, scope.spawn(move || calibrate_on_fixture(board, interrupt, quiet)))
            })
            .collect();
        running
            .into_iter()
            .map(|(name, thread)| Outcome { name, result: thread.join().unwrap_or(Err(Error::BoardThreadFailed)) })
            .collect()
    })
}

/// One board's session on the fixture, its lines named by the board.
fn calibrate_on_fixture(
    board: Board,
    interrupt: Arc<AtomicBool>,
    quiet: bool,
) -> Result<Option<CalibrateReport>, Error> {
    let mut lines = BoardLines { name: board.name, quiet };
    calibrate_board(&board.args, board.opened?, interrupt, &mut lines)
}

/// Prints every board's report (or the one JSON object), then the fixture's outcome: an error
/// naming each board that failed, else one naming each that missed its target.
fn show_all(outcomes: &[Outcome], json: bool) -> Result<(), Error> {
    if json {
        println!("{}", fixture_json(outcomes));
    } else {
        for outcome in outcomes {
            if let Ok(Some(report)) = &outcome.result {
                print!("board {}:\n{}", outcome.name, report::text::calibrate_report(report));
            }
        }
    }
    let failed: Vec<String> = outcomes
        .iter()
        .filter_map(|o| o.result.as_ref().err().map(|error| format!("board {}: {error}", o.name)))
        .collect();
    if !failed.is_empty() {
        let calibrated = outcomes.len() - failed.len();
        return Err(Error::BoardsFailed { failed: failed.join("; "), calibrated, boards: outcomes.len() });
    }
    let missed: Vec<String> = outcomes.iter().filter_map(missed_line).collect();
    match missed.is_empty() {
        true => Ok(()),
        false => Err(Error::TargetMissed { line: missed.join("; ") }),
    }
}

/// "board SERIAL: why" when the board's calibration missed its target.
fn missed_line(outcome: &Outcome) -> Option<String> {
    let Ok(Some(report)) = &outcome.result else { return None };
    let target = report.target.as_ref().filter(|t| t.missed)?;
    Some(format!("board {}: {}", outcome.name, target.line))
}

/// One board in `calibrate --boards/--ports --json`: its `serial` (the port, when it could not be
/// opened) and its report, or its `error`.
#[derive(Serialize)]
struct BoardJson<'a> {
    serial: &'a str,
    #[serde(flatten)]
    report: Option<&'a CalibrateReport>,
    #[serde(skip_serializing_if = "Option::is_none")]
    error: Option<String>,
}

/// `calibrate --boards/--ports --json`.
#[derive(Serialize)]
struct FixtureJson<'a> {
    boards: Vec<BoardJson<'a>>,
}

/// `calibrate --boards/--ports --json`: `boards`, each as [`BoardJson`].
fn fixture_json(outcomes: &[Outcome]) -> String {
    let boards: Vec<BoardJson> = outcomes
        .iter()
        .map(|outcome| {
            let (report, error) = match &outcome.result {
                Ok(Some(report)) => (Some(report), None),
                Ok(None) => (None, Some("not uploaded".to_owned())),
                Err(error) => (None, Some(error.to_string())),
            };
            BoardJson { serial: &outcome.name, report, error }
        })
        .collect();
    // NOTE: the reports hold only numbers, strings, options and maps with string keys, which always
    // serialise (as report::json says of each).
    serde_json::to_string_pretty(&FixtureJson { boards }).unwrap_or_default()
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
