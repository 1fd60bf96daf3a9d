//! The single steps of the procedure on the command line: `capture`, `verify` (the whole of it,
//! `calibrate`, is in [`super::calibrate`]).

use super::args::{CaptureArgs, Device};
use crate::error::Error;
use crate::link::LinkError;
use crate::opened::Opened;
use crate::orientation::Orientation;
use crate::procedure::{self, Feedback};
use crate::session::SessionFiles;
use crate::session::{stem_of, Session};
use crate::terminal::interrupt_on_ctrl_c;
use crate::terminal::Terminal;

/// How far off, in degrees, the tool's hand places the simulated board for `verify --sim`.
const VERIFY_PLACEMENT_DEG: f64 = 3.0;

/// `accelcal capture`: one position, appended to a session file.
pub(super) fn capture(args: &CaptureArgs) -> Result<(), Error> {
    let stem = stem_of(&args.session);
    let mut session = Session::load_or_new(&stem)?;
    let mut opened = args.device.open()?;
    opened.connection.info.sensor.map_err(LinkError::from)?;
    let mut feedback = Terminal::new(true);
    let target = Orientation::named(&args.name);
    // NOTE: the simulated board rests +Z up until turned: a capture named as an orientation is
    // taken there, so that what is stored is what its name says.
    if let (Some(target), Some(_)) = (&target, &opened.sim) {
        opened.hand(0.0).0.present(target, &mut feedback)?;
    }
    let result = opened.connection.client.capture(args.seconds, |p| feedback.progress(p.samples, p.total_samples));
    feedback.progress_done();
    let (stats, face) = result?;
    session.captures.push(crate::session::capture_now(&args.name, target, face, stats));
    session.save(&stem)?;
    let [x, y, z] = stats.mean_g;
    println!(
        "captured {}: mean {x:+.5} {y:+.5} {z:+.5} g over {} samples; {} captures in the session",
        args.name,
        stats.samples,
        session.captures.len()
    );
    Ok(())
}

/// `accelcal verify`. Ctrl-C cancels the capture on the board and says what was verified so far;
/// verifying changes nothing on the board.
pub(super) fn verify(device: &Device, positions: usize) -> Result<(), Error> {
    let mut opened: Opened = device.open()?;
    let mut feedback = Terminal::new(true);
    opened.connection.client.interrupt_on(interrupt_on_ctrl_c());
    let (mut hand, wait_limit) = opened.hand(VERIFY_PLACEMENT_DEG);
    let client = &mut opened.connection.client;
    let v = procedure::verify(client, hand.as_mut(), positions, wait_limit, &mut feedback)
        .map_err(|source| Error::VerifyStopped { source: Box::new(source) })?;
    println!(
        "| |a| - 1 g | rms {:.2} mg raw, {:.3} mg calibrated (worst {:.3} mg); {}",
        v.before_rms_mg,
        v.after_rms_mg,
        v.after_max_mg,
        v.chip_agreement()
    );
    Ok(())
}
