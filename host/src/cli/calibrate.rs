//! `accelcal calibrate` on one board: the session begun (or resumed) and kept in its files, the
//! core's run driven on the board (`run::board::calibrate`: captures, fit, upload, verification, the
//! gyro's turn), then the certificate and the report beside the session.

use crate::session::SessionFiles;
use std::path::Path;
use std::sync::atomic::AtomicBool;
use std::sync::Arc;

use embassy_futures::block_on;

use super::adaptive;
use super::args::CalibrateArgs;
use super::device::Opened;
use super::kept::{self, Kept};
use crate::calibration;
use crate::certificate::Certificate;
use crate::error::Error;
use crate::link::LinkError;
use crate::procedure::{Feedback, Fitted, ProcedureError, TurnCheck, Verification};
use crate::report::{self, CalibrateReport};
use crate::session::{stem_file, Session, SessionKind, TargetVerdict};
use accelcal_core::run::board::{self, Around, BoardPlan, Calibrated, RunError};

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
    let learned = adaptive::learned_model(args, &mut opened.connection.client, feedback)?;
    let kept = kept::start(args, &opened.connection.info, learned, feedback)?;
    opened.connection.client.interrupt_on(interrupt);
    let plan = plan_of(args, &opened, &kept)?;
    let Some(calibrated) = run(args, &mut opened, &plan, &kept, feedback)? else { return Ok(None) };
    finish(args, &opened, calibrated, kept.path.as_deref(), feedback).map(Some)
}

/// How the core's run goes on this board: the capture length or stop rule of the session's kind,
/// the verification asked for, the wait, the board's clock.
fn plan_of(args: &CalibrateArgs, opened: &Opened, kept: &Kept) -> Result<BoardPlan, Error> {
    let rate_hz = opened.connection.info.config.sample_rate_hz;
    let rule = match kept.session.kind {
        SessionKind::Adaptive => {
            Some(args.length.rule(rate_hz).map_err(|e| stopped_at(args, kept.path.as_deref(), e))?)
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
    kept: &Kept,
    feedback: &mut dyn Feedback,
) -> Result<Option<Calibrated>, Error> {
    let path = kept.path.clone();
    let mut keep = |session: &Session| path.as_deref().map_or(Ok(()), |p| session.save(p));
    let Opened { connection, sim, seat, hand_seed, .. } = opened;
    let mut hands = || super::device::hand_for(sim.as_ref(), seat, *hand_seed, args.sim_placement_deg).0;
    let around = Around { feedback, hands: &mut hands, keep: &mut keep };
    let info = connection.info.clone();
    let result = block_on(board::calibrate(connection.client.link(), &info, plan, around, kept.session.clone()));
    result.map_err(|error| match error {
        RunError::Stopped(source) => stopped_at(args, kept.path.as_deref(), source),
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

/// Why a run stopped, with the command that resumes its session when the session file holds a
/// capture.
fn stopped_at(args: &CalibrateArgs, kept_at: Option<&Path>, source: ProcedureError) -> Error {
    match kept_at.map(kept_on_disk) {
        Some((path, captures)) if captures > 0 => {
            Error::Stopped { source: Box::new(source), captures, path, device: device_flags(args) }
        }
        _ => source.into(),
    }
}

/// The session's JSON file and how many captures it holds as written (not as in memory: a capture
/// whose write failed, on a full disk say, is not in it); none when it cannot be read.
fn kept_on_disk(stem: &Path) -> (std::path::PathBuf, usize) {
    let json = stem_file(stem, "json");
    let captures = Session::load(&json).map_or(0, |session| session.captures.len());
    (json, captures)
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
    let mut report = report_of(opened, &calibrated.fitted, calibrated.verification, calibrated.check);
    report.board_seconds = calibrated.board_seconds;
    report.certificate = certificate;
    report.target = Some(calibrated.target);
    Ok(report)
}

/// The run's report: the calibration chosen, the fits beside it, the verification and the gyro's
/// check, and with `--sim` the simulated sensor's truth at the calibration's temperature.
fn report_of(
    opened: &Opened,
    fitted: &Fitted,
    verification: Verification,
    check: Option<TurnCheck>,
) -> CalibrateReport {
    let session_temp_c = calibration::thermal_reference(&fitted.chosen).ref_temp_c;
    let truth = opened.sim.as_ref().map(|board| board.truth_json(session_temp_c));
    let captures = fitted.session.captures.len();
    let chip = fitted.chip.as_ref().map(|c| &c.calibration);
    let mut report = CalibrateReport::new(&fitted.chosen, chip, fitted.host.as_ref(), truth, verification, captures)
        .with_gyro(&fitted.gyro, check);
    report.true_error_mg = opened.sim.as_ref().map(|board| board.true_error_mg(&fitted.chosen, session_temp_c));
    report
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
    let certificate = super::certificate::unless_failed(verified, target, path, feedback)?;
    if let Some(stem) = kept_at {
        let not_kept = |source| Error::VerificationNotKept {
            source: Box::new(source),
            path: stem_file(stem, "json"),
            device: device_flags(args),
        };
        verified.save(stem).map_err(not_kept)?;
        keep_with_report(verified, certificate.as_ref(), stem, feedback)?;
    }
    if let (Some(lot), Some(certificate)) = (args.lot.as_deref(), &certificate) {
        feedback.say(&super::lot::add_issued(lot, certificate)?);
    }
    Ok(certificate)
}

/// Writes the verified session's report and certificate beside it, and says where.
fn keep_with_report(
    session: &Session,
    certificate: Option<&Certificate>,
    stem: &Path,
    feedback: &mut dyn Feedback,
) -> Result<(), Error> {
    let json = stem_file(stem, "json");
    let page = super::report::beside(&json);
    super::report::write_page(&super::report::build(session, &json)?, &page)?;
    let certificate = match certificate {
        Some(certificate) => {
            format!("; certificate to {}", super::certificate::written(certificate, &json)?.0.display())
        }
        None => String::new(),
    };
    feedback.say(&format!("session kept in {}; report written to {}{certificate}", json.display(), page.display()));
    Ok(())
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
