//! The guided procedure on the command line: `calibrate`, `capture`, `verify`.

use std::path::Path;

use shared::{AccelRange, Calibration};

use super::args::{CalibrateArgs, CaptureArgs, Device};
use super::device::Opened;
use super::terminal::{feedback, Terminal};
use crate::calibration::{self, describe};
use crate::error::Error;
use crate::fit::Fit;
use crate::link::{Client, LinkError, Port};
use crate::orientation::Orientation;
use crate::procedure::{self, CollectOptions, Feedback, Verification};
use crate::report::{self, CalibrateReport};
use crate::session::{CaptureRecord, Session};

/// How far off, in degrees, the tool's hand places the simulated board for `verify --sim`.
const VERIFY_PLACEMENT_DEG: f64 = 3.0;

/// The calibrations a calibration chooses between.
struct Fitted {
    session: Session,
    chip: Calibration,
    host: Option<Fit>,
    chosen: Calibration,
}

/// `accelcal calibrate`: captures, fit, upload, save, verification.
pub(super) fn calibrate(args: &CalibrateArgs) -> Result<(), Error> {
    let mut opened = args.device.open()?;
    opened.connection.info.sensor.map_err(LinkError::from)?;
    let yes = args.yes || (args.json && opened.sim.is_some());
    let mut feedback = feedback(args.json, yes);
    let (mut hand, wait_limit) = opened.hand(args.sim_placement_deg, args.device.seed);
    let options = CollectOptions { seconds: args.seconds, wait_limit };
    let range = opened.connection.info.config.range;
    let client = &mut opened.connection.client;
    let session =
        procedure::collect(client, hand.as_mut(), &procedure::targets(args.quick), &options, feedback.as_mut())?;
    if let Some(path) = &args.session {
        session.save(path)?;
    }
    let fitted = choose(client, session, range, args.quick)?;
    show_choice(feedback.as_mut(), &fitted);
    if !upload_if_confirmed(client, &fitted.chosen, feedback.as_mut())? {
        return Ok(());
    }
    let verification = procedure::verify(client, hand.as_mut(), args.verify, wait_limit, feedback.as_mut())?;
    if let Some(path) = &args.session {
        keep_with_report(&fitted.session, &verification, path, feedback.as_mut())?;
    }
    let truth = opened.sim.as_ref().map(|board| board.truth());
    let captures = fitted.session.captures.len();
    let report =
        CalibrateReport::new(&fitted.chosen, &fitted.chip, fitted.host.as_ref(), truth, verification, captures);
    print_report(&report, args.json);
    Ok(())
}

/// Saves the session again with its verification, writes its report beside it, and says where.
fn keep_with_report(
    session: &Session,
    verification: &Verification,
    stem: &Path,
    feedback: &mut dyn Feedback,
) -> Result<(), Error> {
    let session = Session { verification: Some(verification.clone()), ..session.clone() };
    session.save(stem)?;
    let json = stem.with_extension("json");
    let page = super::report::beside(&json);
    super::report::write_page(&super::report::build(&session, &json)?, &page)?;
    feedback.say(&format!("session kept in {}; report written to {}", json.display(), page.display()));
    Ok(())
}

/// Uploads and saves the calibration if the user agrees; whether it did.
fn upload_if_confirmed<P: Port>(
    client: &mut Client<P>,
    calibration: &Calibration,
    feedback: &mut dyn Feedback,
) -> Result<bool, Error> {
    if !feedback.confirm("Upload this calibration to the board and save it in flash?") {
        feedback.say("not uploaded; the board keeps its previous calibration");
        return Ok(false);
    }
    client.set_calibration(*calibration)?;
    client.save_calibration()?;
    feedback.say("uploaded and saved; now checking it at fresh orientations");
    Ok(true)
}

/// The on-chip fit, and for a full calibration the host's fit, which is then the one chosen.
fn choose<P: Port>(client: &mut Client<P>, session: Session, range: AccelRange, quick: bool) -> Result<Fitted, Error> {
    let chip = client.fit_six_position()?;
    if quick {
        return Ok(Fitted { session, chip, host: None, chosen: chip });
    }
    let fit = procedure::host_fit(&session)?;
    let chosen = calibration::from_fit(&fit, &session, range)?;
    Ok(Fitted { session, chip, host: Some(fit), chosen })
}

/// The chosen calibration, the host fit's parameters, and the chip's fit beside them.
fn show_choice(feedback: &mut dyn Feedback, fitted: &Fitted) {
    feedback.say(&describe(&fitted.chosen));
    if let Some(fit) = &fitted.host {
        for p in &fit.parameters {
            let error = p.std_error.map_or(String::new(), |e| format!(" +- {e:.1e}"));
            feedback.say(&format!("  {:<5} {:+.6}{error}", p.name, p.value));
        }
        feedback.say(&format!("on-chip six-position fit for comparison: {}", describe(&fitted.chip)));
    }
}

fn print_report(report: &CalibrateReport, json: bool) {
    if json {
        println!("{}", report::json::calibrate_report(report));
    } else {
        print!("{}", report::text::calibrate_report(report));
    }
}

/// `accelcal capture`: one position, appended to a session file.
pub(super) fn capture(args: &CaptureArgs) -> Result<(), Error> {
    let mut session = Session::load_or_new(&args.session)?;
    let mut opened = args.device.open()?;
    opened.connection.info.sensor.map_err(LinkError::from)?;
    let mut feedback = Terminal::new(true);
    let result = opened.connection.client.capture(args.seconds, |p| feedback.progress(p.samples, p.total_samples));
    feedback.progress_done();
    let (stats, face) = result?;
    session.captures.push(CaptureRecord::now(&args.name, Orientation::named(&args.name), face, stats));
    session.save(&args.session)?;
    let [x, y, z] = stats.mean_g;
    println!(
        "captured {}: mean {x:+.5} {y:+.5} {z:+.5} g over {} samples; {} captures in the session",
        args.name,
        stats.samples,
        session.captures.len()
    );
    Ok(())
}

/// `accelcal verify`.
pub(super) fn verify(device: &Device, positions: usize) -> Result<(), Error> {
    let mut opened: Opened = device.open()?;
    let mut feedback = Terminal::new(true);
    let (mut hand, wait_limit) = opened.hand(VERIFY_PLACEMENT_DEG, device.seed);
    let client = &mut opened.connection.client;
    let v = procedure::verify(client, hand.as_mut(), positions, wait_limit, &mut feedback)?;
    println!(
        "| |a| - 1 g | rms {:.2} mg raw, {:.3} mg calibrated (worst {:.3} mg); chip and host agree within {:.2} mg",
        v.before_rms_mg, v.after_rms_mg, v.after_max_mg, v.on_chip_difference_mg
    );
    Ok(())
}
