//! What a board's run uploads: the chip's fit or the host's, chosen and shown, with the gyro's G
//! fitted to the moves between the positions.

use shared::protocol::SensorConfig;
use shared::Calibration;

use super::{Feedback, Moves, ProcedureError};
use crate::calibration::describe;
use crate::fit::{drift, Fit};
use crate::limits::DRIFT_MIN_CHANGE_C;
use crate::link::{ChipOrtho9, Link, Transport};
use crate::report::gyro::GyroOutcome;
use crate::session::{Outcome, Session, SessionKind};

/// The calibrations a run chooses between.
pub struct Fitted {
    pub session: Session,
    pub chip: Option<ChipOrtho9>,
    pub host: Option<Fit>,
    pub chosen: Calibration,
    /// The gyro's G fitted to the moves (put into `chosen`), or why not.
    pub gyro: GyroOutcome,
}

/// The accelerometer's calibration chosen, and the gyro's G fitted to the moves and put into it;
/// the session keeps the turns.
pub(super) async fn fit_with_gyro<T: Transport>(
    link: &mut Link<T>,
    session: &Session,
    resumed: bool,
    config: SensorConfig,
    moves: &Moves,
    feedback: &mut dyn Feedback,
) -> Result<Fitted, ProcedureError> {
    let mut fitted = choose(link, session, resumed, config, feedback).await?;
    let (chosen, gyro) = super::gyro::fit(moves, resumed, &fitted.session, &fitted.chosen, feedback);
    fitted.chosen = chosen;
    // NOTE: a resumed run that turned nothing keeps the turns the session recorded before.
    let turns = super::gyro::summaries(moves, &fitted.session, &chosen, &gyro);
    fitted.session.gyro_turns = turns.or(fitted.session.gyro_turns.take());
    fitted.gyro = gyro;
    Ok(fitted)
}

/// The on-chip fit (of captures all taken in this run), and but for a quick session the host's fit,
/// which is then the one chosen; a resumed `--chip-fit` session is fitted by the same solver on the
/// host.
async fn choose<T: Transport>(
    link: &mut Link<T>,
    session: &Session,
    resumed: bool,
    config: SensorConfig,
    feedback: &mut dyn Feedback,
) -> Result<Fitted, ProcedureError> {
    let session = session.clone();
    // NOTE: an adaptive session's chip fit is only for comparison: one it cannot make is not an error.
    let chip = match (resumed, session.kind) {
        (true, _) => None,
        (false, SessionKind::Adaptive) => link.fit_ortho9().await.ok(),
        (false, _) => Some(link.fit_ortho9().await?),
    };
    let (host, chosen) = match (session.kind, chip) {
        (SessionKind::Quick, Some(chip)) => (None, chip.calibration),
        _ => outcome(&session, config, feedback).map(|o| (Some(o.fit), o.calibration))?,
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

/// The calibration of a session, with what the temperature did during an adaptive one said.
pub fn outcome(
    session: &Session,
    config: SensorConfig,
    feedback: &mut dyn Feedback,
) -> Result<Outcome, ProcedureError> {
    let outcome = session.outcome(config)?;
    if session.kind != SessionKind::Adaptive {
        return Ok(outcome);
    }
    let (low, high) = drift::span_c(&outcome.fitted.captures);
    if let Some(model) = outcome.fitted.learned {
        feedback.say(&format!(
            "the temperature moved {:.2} degC during the session ({low:.2} to {high:.2} degC); the captures were \
             corrected by the board's learned temperature model (around {:.1} degC), which stays with the calibration",
            high - low,
            model.ref_temp_c
        ));
        return Ok(outcome);
    }
    match outcome.fitted.drift {
        Some(d) => feedback.say(&format!(
            "the temperature moved {:.2} degC during the session ({low:.2} to {high:.2} degC); the offset drift it \
             caused ({:+.2}, {:+.2}, {:+.2} mg/degC) was fitted with the calibration and goes with it to the board",
            high - low,
            d.slope_g_per_c[0] * 1e3,
            d.slope_g_per_c[1] * 1e3,
            d.slope_g_per_c[2] * 1e3
        )),
        None if high - low >= DRIFT_MIN_CHANGE_C => feedback.say(&format!(
            "the temperature moved {:.2} degC during the session; too few positions to fit the drift it caused",
            high - low
        )),
        None => {}
    }
    Ok(outcome)
}
