//! The gyro's part of a board's run: G fitted to the moves recorded between the positions and put
//! into the calibration to upload, and after the upload the verification turn.

use shared::Calibration;

use super::{check_turn, fit_moves, turn_summaries, Feedback, Hand, Moves, ProcedureError, TurnCheck};
use crate::calibration;
use crate::fit::gyro::TurnSummary;
use crate::link::{Link, Transport};
use crate::report::gyro::GyroOutcome;
use crate::run::resume;
use crate::session::Session;

/// `chosen` with G fitted to the recorded moves when they allow it, and what the fit gave; every
/// dropped move and the reason for no fit (with the turns to add) are said.
pub(super) fn fit(
    moves: &Moves,
    resumed: bool,
    session: &Session,
    chosen: &Calibration,
    feedback: &mut dyn Feedback,
) -> (Calibration, GyroOutcome) {
    let mut outcome = GyroOutcome { dropped_moves: moves.dropped.clone(), ..GyroOutcome::default() };
    moves.dropped.iter().for_each(|d| feedback.say(&format!("gyro: {d}")));
    let result = fit_moves(&moves.recorded, session, chosen)
        .map_err(|e| e.to_string())
        .and_then(|fit| calibration::with_gyro(chosen, &fit).map(|c| (c, fit)).map_err(|e| e.to_string()));
    match result {
        Ok((calibration, fit)) => {
            feedback.say(&format!("gyro: G fitted to {} turns, residual {:.3} degrees", fit.turns, fit.residual_deg));
            outcome.fit = Some(fit);
            (calibration, outcome)
        }
        Err(why) => {
            let (calibration, outcome, said) = resume::gyro_without_fit(why, resumed, session, chosen, outcome);
            feedback.say(&said);
            (calibration, outcome)
        }
    }
}

/// The recorded turns as the session keeps them for its report, calibrated with the fitted G (the
/// identity without one); `None` when no move was recorded.
pub(super) fn summaries(
    moves: &Moves,
    session: &Session,
    chosen: &Calibration,
    outcome: &GyroOutcome,
) -> Option<Vec<TurnSummary>> {
    let g = outcome.fit.as_ref().map_or(shared::linalg::identity(), |f| f.matrix);
    let summaries = turn_summaries(&moves.recorded, session, chosen, &g);
    (!summaries.is_empty()).then_some(summaries)
}

/// The verification turn on the uploaded calibration; `None` (said) when it could not be measured.
pub(super) async fn check<T: Transport>(
    link: &mut Link<T>,
    hand: &mut dyn Hand,
    rate_hz: u16,
    outcome: &GyroOutcome,
    feedback: &mut dyn Feedback,
) -> Result<Option<TurnCheck>, ProcedureError> {
    // NOTE: a measured turn is shown with the report at the end; only why there is none is said here.
    let result = check_turn(link, hand, rate_hz, outcome.fit.as_ref(), feedback).await?;
    if let Err(why) = &result {
        feedback.say(why);
    }
    Ok(result.ok())
}
