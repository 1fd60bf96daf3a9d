//! `accelcal calibrate`: captures (kept in a session after each one, resumable), fit, upload, save,
//! verification.

use crate::session::SessionFiles;
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use shared::Calibration;

use super::adaptive;
use super::args::CalibrateArgs;
use super::choice::{fit_with_gyro, show_choice, Fitted};
use super::device::Opened;
use super::kept::{self, Kept};
use crate::calibration;
use crate::certificate::Certificate;
use crate::error::Error;
use crate::link::{Client, LinkError, Port};
use crate::procedure::{self, CollectOptions, Feedback, Moves, ProcedureError, TurnCheck, Turning, Verification};
use crate::report::{self, CalibrateReport};
use crate::session::{stem_file, Session, SessionError, SessionKind, TargetVerdict};
use accelcal_core::run::resume;

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
    let mut kept = kept::start(args, &opened.connection.info, learned, feedback)?;
    opened.connection.client.interrupt_on(interrupt.clone());
    let (moves, first_capture_s) = collect(args, &mut opened, &mut kept, feedback)?;
    let fitted = fit_with_gyro(&mut opened, &kept, &moves, feedback)?;
    show_choice(feedback, &fitted);
    let client = &mut opened.connection.client;
    // NOTE: the captures are all kept by now: a Ctrl-C or a lost board here is resumed from them.
    let stopped = |source: LinkError| stopped_at(args, kept.path.as_deref(), source.into());
    if interrupt.load(Ordering::SeqCst) {
        return Err(stopped(LinkError::Interrupted));
    }
    if !upload_if_confirmed(client, &fitted.chosen, &interrupt, feedback).map_err(stopped)? {
        return Ok(None);
    }
    // NOTE: kept before the verification, so that a Ctrl-C or a pulled cable during it still leaves
    // the session saying what the board holds.
    if let Some(path) = kept.path.as_deref() {
        resume::kept_before_verifying(&fitted.session, fitted.chosen).save(path)?;
    }
    let first_capture_s = resume::board_time_start(first_capture_s, kept.resumed);
    finish(args, &mut opened, &fitted, kept.path.as_deref(), first_capture_s, feedback).map(Some)
}

/// Prints a board's report; an error when it missed its target (exit status 2).
pub(super) fn show(report: &CalibrateReport, json: bool) -> Result<(), Error> {
    print_report(report, json);
    match &report.target {
        Some(target) if target.missed => Err(Error::TargetMissed { line: target.line.clone() }),
        _ => Ok(()),
    }
}

/// The captures the session lacks, written after each one, and the moves between them; an error
/// names where the captures are kept. Also the board's clock when the first capture started (when
/// collection started, with fixed lengths).
fn collect(
    args: &CalibrateArgs,
    opened: &mut Opened,
    kept: &mut Kept,
    feedback: &mut dyn Feedback,
) -> Result<(Moves, Option<f64>), Error> {
    let (mut hand, wait_limit) = opened.hand(args.sim_placement_deg);
    let path = kept.path.clone();
    let mut keep = |session: &Session| path.as_deref().map_or(Ok(()), |p| session.save(p));
    let mut moves = Moves::at(opened.connection.info.config.sample_rate_hz);
    let (turning, session) = (Turning { hand: hand.as_mut(), moves: &mut moves }, &mut kept.session);
    let result = if session.kind == SessionKind::Adaptive {
        adaptive::collect(args, opened, turning, wait_limit, session, &mut keep, feedback)
    } else {
        collect_fixed(args, opened, turning, wait_limit, session, &mut keep, feedback)
    };
    result.map(|first| (moves, first)).map_err(|source| stopped_at(args, kept.path.as_deref(), source))
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

/// Collects with a fixed capture length (`--seconds`, or `--quick`'s); the board's clock when the
/// collection started.
fn collect_fixed(
    args: &CalibrateArgs,
    opened: &mut Opened,
    turning: Turning<'_>,
    wait_limit: Option<std::time::Duration>,
    session: &mut Session,
    keep: &mut dyn FnMut(&Session) -> Result<(), SessionError>,
    feedback: &mut dyn Feedback,
) -> Result<Option<f64>, ProcedureError> {
    let seconds = args.seconds.unwrap_or_else(|| procedure::capture_seconds(session.kind == SessionKind::Quick));
    let options = CollectOptions { seconds, wait_limit };
    let (targets, started) = (procedure::targets(session.kind == SessionKind::Quick), opened.clock()());
    let client = &mut opened.connection.client;
    procedure::collect_into(client, turning, &targets, &options, feedback, session, keep).map(|()| Some(started))
}

/// The verification, the session kept with it and its report beside it, then the result.
fn finish(
    args: &CalibrateArgs,
    opened: &mut Opened,
    fitted: &Fitted,
    kept_at: Option<&Path>,
    first_capture_s: Option<f64>,
    feedback: &mut dyn Feedback,
) -> Result<CalibrateReport, Error> {
    let kind = fitted.session.kind;
    let (mut hand, wait_limit) = opened.hand(args.sim_placement_deg);
    let (positions, length) = adaptive::verification(args, kind, opened.connection.info.config.sample_rate_hz)?;
    let (rate_hz, clock) = (opened.connection.info.config.sample_rate_hz, opened.clock());
    let client = &mut opened.connection.client;
    let calibrated: Vec<[f64; 3]> = fitted.session.captures.iter().map(|c| c.stats.mean_g.map(f64::from)).collect();
    let on_board = |source| Error::AfterUpload { source: Box::new(source), check_later: check_later(args) };
    let verification =
        procedure::verify_with(client, hand.as_mut(), positions, wait_limit, feedback, &calibrated, length)
            .map_err(on_board)?;
    let board_seconds = first_capture_s.map(|first| clock() - first);
    let check = super::gyro::check(client, hand.as_mut(), rate_hz, &fitted.gyro, feedback).map_err(on_board)?;
    let uploaded = Some(fitted.chosen);
    let target = verification.against((kind == SessionKind::Adaptive).then_some(args.length.target_mg));
    let verified = Session { verification: Some(verification.clone()), uploaded, ..fitted.session.clone() };
    let certificate = certify(&verified, &target, kept_at, args, feedback)?;
    let mut report = report_of(opened, fitted, verification, check);
    report.board_seconds = board_seconds;
    report.certificate = certificate;
    report.target = Some(target);
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

/// Uploads and saves the calibration if the user agrees; whether it did. Ctrl-C at the question
/// ends the run at once (`Interrupted`).
fn upload_if_confirmed<P: Port>(
    client: &mut Client<P>,
    calibration: &Calibration,
    interrupt: &AtomicBool,
    feedback: &mut dyn Feedback,
) -> Result<bool, LinkError> {
    if !feedback.confirm("Upload this calibration to the board and save it in flash?") {
        if interrupt.load(Ordering::SeqCst) {
            return Err(LinkError::Interrupted);
        }
        feedback.say("not uploaded; the board keeps its previous calibration");
        return Ok(false);
    }
    client.set_calibration(*calibration)?;
    client.save_calibration()?;
    feedback.say("uploaded and saved; now checking it at fresh orientations");
    Ok(true)
}

fn print_report(report: &CalibrateReport, json: bool) {
    if json {
        println!("{}", report::json::calibrate_report(report));
    } else {
        print!("{}", report::text::calibrate_report(report));
    }
}
