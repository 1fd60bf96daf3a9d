//! `accelcal calibrate` on one board: the session begun (or resumed) and kept in its files, the
//! core's run driven on the board (`run::board::calibrate`: captures, fit, upload, verification, the
//! gyro's turn), then the certificate and the report beside the session.

use crate::session::SessionFiles;
use std::path::Path;
use std::sync::atomic::AtomicBool;
use std::sync::Arc;

use embassy_futures::block_on;
use shared::protocol::DeviceInfo;
use shared::Calibration;

use super::args::CalibrateArgs;
use crate::certificate::Certificate;
use crate::ended;
use crate::error::Error;
use crate::link::LinkError;
use crate::opened::Opened;
use crate::procedure::thermal::learned::kept_by_new_session;
use crate::procedure::Feedback;
use crate::report::{self, CalibrateReport};
use crate::session::{
    holder, new_session_path, stem_file, BoardRecord, KeptSession, Session, SessionKind, TargetVerdict,
};
use accelcal_core::run::board::{self, Around, BoardPlan, Calibrated, RunError};
use accelcal_core::run::resume::resumed_as_begun;

/// One board's session, from its first capture to its verified report (`None`: the upload was
/// declined); the same for a board alone and for each board on a fixture.
pub(super) fn calibrate_board(
    args: &CalibrateArgs,
    mut opened: Opened,
    interrupt: Arc<AtomicBool>,
    feedback: &mut dyn Feedback,
) -> Result<Option<CalibrateReport>, Error> {
    opened.connection.info.sensor.map_err(LinkError::from)?;
    if args.serial.is_some() {
        let reported = String::from_utf8_lossy(&opened.connection.info.serial.hex()).into_owned();
        return Err(Error::SerialOfItsOwn { reported });
    }
    opened.hand_seed = args.sim_hand_seed.unwrap_or(args.device.seed);
    let learned =
        match args.resume.is_none() && SessionKind::asked(args.chip_fit, args.seconds) == SessionKind::Adaptive {
            true => kept_by_new_session(&mut opened.connection.client, feedback)?,
            false => None,
        };
    let kept = kept(args, &opened.connection.info, learned, feedback)?;
    opened.connection.client.interrupt_on(interrupt);
    let plan = plan_of(args, &opened, &kept)?;
    let Some(calibrated) = run(args, &mut opened, &plan, &kept, feedback)? else { return Ok(None) };
    finish(args, &opened, calibrated, kept.path.as_deref(), feedback).map(Some)
}

/// The session to continue (`--resume`, checked against the board) or a new one, written at once
/// so that an unwritable path fails before the first capture.
fn kept(
    args: &CalibrateArgs,
    info: &DeviceInfo,
    learned: Option<Calibration>,
    feedback: &mut dyn Feedback,
) -> Result<KeptSession, Error> {
    let board = BoardRecord::of(info);
    let holder = holder(&format!("board {}", board.serial));
    let kept = match &args.resume {
        Some(path) => {
            let (kept, said) = KeptSession::resume(path, &board, &holder)?;
            feedback.say(&said);
            resumed_as_begun(kept.session.kind, args.chip_fit, args.seconds).iter().for_each(|line| feedback.say(line));
            kept
        }
        None => {
            // NOTE: a simulated board in this process is gone after the run: nothing to keep by default.
            let place =
                new_session_path(args.session.as_deref(), args.device.port.is_some(), Some(&board.serial), &holder)?;
            let session = Session {
                board: Some(board),
                kind: SessionKind::asked(args.chip_fit, args.seconds),
                learned,
                ..Session::default()
            };
            KeptSession::new(session, place)
        }
    };
    if let Some(path) = &kept.path {
        kept.session.save(path)?;
        feedback.say(&format!("the captures are kept in {} as they are taken", stem_file(path, "json").display()));
    }
    Ok(kept)
}

/// How the core's run goes on this board: the capture length or stop rule of the session's kind,
/// the verification asked for, the wait, the board's clock.
fn plan_of(args: &CalibrateArgs, opened: &Opened, kept: &KeptSession) -> Result<BoardPlan, Error> {
    let rate_hz = opened.connection.info.config.sample_rate_hz;
    let rule = match kept.session.kind {
        SessionKind::Adaptive => {
            Some(args.length.rule(rate_hz).map_err(|e| ended::stopped(e, kept.path.as_deref(), device_flags(args)))?)
        }
        _ => None,
    };
    let wait_limit = opened.hand(args.sim_placement_deg).1;
    let (seconds, verify_positions, clock, resumed) = (args.seconds, args.verify, opened.clock(), kept.resumed);
    Ok(BoardPlan { seconds, rule, verify_positions, wait_limit, clock, resumed })
}

/// The core's run on the board, its session kept in its files after every capture; its errors as
/// the command line names them, each with the way on.
fn run(
    args: &CalibrateArgs,
    opened: &mut Opened,
    plan: &BoardPlan,
    kept: &KeptSession,
    feedback: &mut dyn Feedback,
) -> Result<Option<Calibrated>, Error> {
    let path = kept.path.clone();
    let mut keep = |session: &Session| path.as_deref().map_or(Ok(()), |p| session.save(p));
    let Opened { connection, sim, seat, hand_seed, .. } = opened;
    let mut hands = || crate::opened::hand_for(sim.as_ref(), seat, *hand_seed, args.sim_placement_deg).0;
    let around = Around { feedback, hands: &mut hands, keep: &mut keep };
    let info = connection.info.clone();
    let result = block_on(board::calibrate(connection.client.link(), &info, plan, around, kept.session.clone()));
    result.map_err(|error| match error {
        RunError::Stopped(source) => ended::stopped(source, kept.path.as_deref(), device_flags(args)),
        RunError::NotKept(source) => source.into(),
        RunError::AfterUpload(source) => {
            Error::AfterUpload { source: Box::new(source), check_later: check_later(args) }
        }
    })
}

/// Prints a board's report; an error when it missed its target (exit status 2).
pub(super) fn show(report: &CalibrateReport, json: bool) -> Result<(), Error> {
    print_report(report, json);
    match &report.target {
        Some(target) if target.missed => Err(Error::TargetMissed { line: target.line.clone() }),
        _ => Ok(()),
    }
}

/// The verified run's certificate, the session kept with it and its report beside it, then the
/// report of the run.
fn finish(
    args: &CalibrateArgs,
    opened: &Opened,
    calibrated: Calibrated,
    kept_at: Option<&Path>,
    feedback: &mut dyn Feedback,
) -> Result<CalibrateReport, Error> {
    let certificate = certify(&calibrated.verified, &calibrated.target, kept_at, args, feedback)?;
    let mut report = opened.report(&calibrated.fitted, calibrated.verification, calibrated.check);
    report.board_seconds = calibrated.board_seconds;
    report.certificate = certificate;
    report.target = Some(calibrated.target);
    Ok(report)
}

/// The verified session's certificate, kept with the session (`kept_at`) and its report, and added
/// to the `lot` database when one is given; none when the calibration failed its own check (the
/// session and its report are kept all the same).
fn certify(
    verified: &Session,
    target: &TargetVerdict,
    kept_at: Option<&Path>,
    args: &CalibrateArgs,
    feedback: &mut dyn Feedback,
) -> Result<Option<Certificate>, Error> {
    let path = kept_at.unwrap_or(Path::new("the session"));
    let certificate = ended::unless_failed(verified, target, path, feedback)?;
    let not_kept = |source| Error::VerificationNotKept {
        source: Box::new(source),
        path: stem_file(path, "json"),
        device: device_flags(args),
    };
    ended::keep_verified(verified, certificate.as_ref(), (kept_at, args.lot.as_deref()), not_kept, feedback)?;
    Ok(certificate)
}

/// The device flags that reach the same board again, for the resume hint.
fn device_flags(args: &CalibrateArgs) -> String {
    match &args.device.port {
        Some(port) => format!("--port {port}"),
        None => format!("--sim --seed {}", args.device.seed),
    }
}

/// How to check an uploaded calibration after this run.
// NOTE: `--sim`'s board lives in this process: a later `verify --sim` gets a fresh board without it.
fn check_later(args: &CalibrateArgs) -> String {
    match &args.device.port {
        Some(port) => format!("check it with `accelcal verify --port {port}`"),
        None => "the simulated board ended with this run, so it cannot be checked later; to keep a simulated \
                 board between commands, serve one with `accelcal sim --pty` and run `accelcal calibrate --port PTY`, \
                 then `accelcal verify --port PTY`"
            .to_owned(),
    }
}

fn print_report(report: &CalibrateReport, json: bool) {
    if json {
        println!("{}", report::json::calibrate_report(report));
    } else {
        print!("{}", report::text::calibrate_report(report));
    }
}
