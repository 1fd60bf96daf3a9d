//! `calibrate` with several boards on one fixture (`--ports`, `--all-boards`, `--sim --boards N`):
//! each board's arguments and the board opened, seated on one fixture (`procedure::Fixture`), and
//! its one-board session (`calibrate_board`) run with the others (`procedure::together`).

use super::args::CalibrateArgs;
use super::calibrate::calibrate_board;
use crate::error::Error;
use crate::link::{find_boards, serial_ports};
use crate::opened::{seat_together, Opened};
use crate::procedure::together::{make_session_folder, run_together, session_path};
use crate::report::fixture::FixtureReport;
use crate::session::{unix_time_s, BoardRecord};
use crate::sim::SimSensor;
use crate::terminal::interrupt_on_ctrl_c;

/// Whether `calibrate` was given a fixture (several boards, or a list of ports) rather than one board.
pub(super) fn holds_several(args: &CalibrateArgs) -> bool {
    args.fixture.boards > 1 || !args.fixture.ports.is_empty() || args.fixture.all_boards
}

/// A board on the fixture: the arguments its session runs with, and the board opened (or why not).
struct Board {
    args: CalibrateArgs,
    opened: Result<Opened, Error>,
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
    seat_together(boards.iter_mut().map(|(_, board)| board.opened.as_mut().ok()).collect(), args.fixture.sim_pull);
    let interrupt = interrupt_on_ctrl_c();
    let report = run_together(boards, args.json && args.device.sim, |board: Board, lines| {
        calibrate_board(&board.args, board.opened?, interrupt.clone(), lines)
    });
    show_all(&report, args.json)
}

/// Every board of the fixture, named by its serial number (or the port it could not be opened on),
/// each with its own arguments; a board that cannot be opened is kept with its cause (the others go
/// on), none at all is an error.
fn open_all(args: &CalibrateArgs) -> Result<Vec<(String, Board)>, Error> {
    let started_s = unix_time_s() as u64;
    let devices: Vec<(String, CalibrateArgs)> = if args.device.sim {
        (0..u64::from(args.fixture.boards))
            .map(|k| (format!("simulated board {}", k + 1), simulated(args, k)))
            .collect()
    } else {
        ports_of(args)?.into_iter().map(|port| (port.clone(), on_port(args, port))).collect()
    };
    make_session_folder(args.session.as_deref())?;
    Ok(devices.into_iter().map(|(name, board_args)| open_board(name, board_args, started_s)).collect())
}

/// Opens one board and names it by its serial number, its session kept under that name.
fn open_board(name: String, mut args: CalibrateArgs, started_s: u64) -> (String, Board) {
    if !args.device.sim {
        // NOTE: each port is listened to (1.2 s) before anything is written to it: say so, it takes seconds.
        eprintln!("{name}: listening, then greeting it if it stays silent");
    }
    let opened = args.device.open();
    let name = match &opened {
        Ok(opened) => BoardRecord::of(&opened.connection.info).serial,
        Err(_) => name,
    };
    args.session = session_path(args.session.as_deref(), &name, started_s, args.device.port.is_some());
    (name, Board { args, opened })
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

/// Prints every board's report (or the one JSON object), then the fixture's outcome: an error
/// naming each board that failed, else one naming each that missed its target.
fn show_all(report: &FixtureReport, json: bool) -> Result<(), Error> {
    if json {
        println!("{}", report.json());
    } else {
        print!("{}", report.text());
    }
    if let Some(failed) = report.failed() {
        return Err(Error::BoardsFailed { failed, calibrated: report.not_failed(), boards: report.boards.len() });
    }
    report.missed().map_or(Ok(()), |line| Err(Error::TargetMissed { line }))
}
