//! What `calibrate` uploads: the chip's fit or the host's, chosen and shown, with the gyro's G
//! fitted to the moves between the positions.

use shared::protocol::SensorConfig;
use shared::Calibration;

use super::adaptive;
use super::device::Opened;
use super::kept::Kept;
use crate::calibration::describe;
use crate::error::Error;
use crate::fit::Fit;
use crate::link::{ChipOrtho9, Client, Port};
use crate::procedure::{Feedback, Moves};
use crate::report::gyro::GyroOutcome;
use crate::session::{Session, SessionKind};

/// The calibrations a calibration chooses between.
pub(super) struct Fitted {
    pub session: Session,
    pub chip: Option<ChipOrtho9>,
    pub host: Option<Fit>,
    pub chosen: Calibration,
    /// The gyro's G fitted to the moves (put into `chosen`), or why not.
    pub gyro: GyroOutcome,
}

/// The accelerometer's calibration chosen, and the gyro's G fitted to the moves and put into it;
/// the session keeps the turns.
pub(super) fn fit_with_gyro(
    opened: &mut Opened,
    kept: &Kept,
    moves: &Moves,
    feedback: &mut dyn Feedback,
) -> Result<Fitted, Error> {
    let config = opened.connection.info.config;
    let mut fitted = choose(&mut opened.connection.client, kept, config, feedback)?;
    let (chosen, gyro) = super::gyro::fit(moves, kept.resumed, &fitted.session, &fitted.chosen, feedback);
    fitted.chosen = chosen;
    // NOTE: a resumed run that turned nothing keeps the turns the session recorded before.
    let turns = super::gyro::summaries(moves, &fitted.session, &chosen, &gyro);
    fitted.session.gyro_turns = turns.or(fitted.session.gyro_turns.take());
    fitted.gyro = gyro;
    Ok(fitted)
}

/// The on-chip fit (of captures all taken in this run), and but for a quick session the host's fit,
/// which is then the one chosen; a resumed `--quick` session is fitted by the same solver on the
/// host.
fn choose<P: Port>(
    client: &mut Client<P>,
    kept: &Kept,
    config: SensorConfig,
    feedback: &mut dyn Feedback,
) -> Result<Fitted, Error> {
    let session = kept.session.clone();
    // NOTE: an adaptive session's chip fit is only for comparison: one it cannot make is not an error.
    let chip = match (kept.resumed, session.kind) {
        (true, _) => None,
        (false, SessionKind::Adaptive) => client.fit_ortho9().ok(),
        (false, _) => Some(client.fit_ortho9()?),
    };
    let (host, chosen) = match (session.kind, chip) {
        (SessionKind::Quick, Some(chip)) => (None, chip.calibration),
        _ => adaptive::outcome(&session, config, feedback).map(|o| (Some(o.fit), o.calibration))?,
    };
    Ok(Fitted { session, chip, host, chosen, gyro: GyroOutcome::default() })
}

/// The chosen calibration, the host fit's parameters, and the chip's fit beside them.
pub(super) fn show_choice(feedback: &mut dyn Feedback, fitted: &Fitted) {
    feedback.say(&describe(&fitted.chosen));
    if let Some(fit) = &fitted.host {
        for p in &fit.parameters {
            let error = p.std_error.map_or(String::new(), |e| format!(" +- {e:.1e}"));
            feedback.say(&format!("  {:<5} {:+.6}{error}", p.name, crate::report::shown(p.value, 6)));
        }
    }
    match (&fitted.chip, &fitted.host) {
        (Some(chip), Some(_)) => {
            feedback.say(&format!("on-chip ortho9 fit for comparison: {}", describe(&chip.calibration)))
        }
        (Some(chip), None) => feedback.say(&format!(
            "fitted on the chip (ortho9, f32): {} captures, | |a| - 1 g | rms {:.3} mg over them, {} iterations",
            chip.captures, chip.calibration.residual_mg, chip.iterations
        )),
        _ => {}
    }
}
