//! The gyro's part of `accelcal calibrate`: G fitted to the moves recorded between the positions
//! and put into the calibration to upload, and after the upload the verification turn.

use shared::calibration::GyroCalibration;
use shared::Calibration;

use crate::calibration;
use crate::fit::gyro::TurnSummary;
use crate::link::{Client, Port};
use crate::procedure::{self, Feedback, Hand, Moves, ProcedureError, TurnCheck};
use crate::report::gyro::GyroOutcome;
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
    let result = procedure::fit_moves(&moves.recorded, session, chosen)
        .map_err(|e| e.to_string())
        .and_then(|fit| calibration::with_gyro(chosen, &fit).map(|c| (c, fit)).map_err(|e| e.to_string()));
    match result {
        Ok((calibration, fit)) => {
            feedback.say(&format!("gyro: G fitted to {} turns, residual {:.3} degrees", fit.turns, fit.residual_deg));
            outcome.fit = Some(fit);
            (calibration, outcome)
        }
        Err(why) => without_fit(why, resumed, session, chosen, outcome, feedback),
    }
}

/// `chosen` when no G could be fitted to this run's moves: with the G this session uploaded in an
/// earlier run, when it was resumed after one; else as it is, said why.
fn without_fit(
    why: String,
    resumed: bool,
    session: &Session,
    chosen: &Calibration,
    mut outcome: GyroOutcome,
    feedback: &mut dyn Feedback,
) -> (Calibration, GyroOutcome) {
    if let (true, Some(matrix)) = (resumed, earlier_g(session)) {
        feedback.say(
            "gyro: G kept from the calibration this session uploaded in an earlier run (the moves it was fitted \
             to are not kept to fit again)",
        );
        return (Calibration { gyro: GyroCalibration { matrix, ..chosen.gyro }, ..*chosen }, outcome);
    }
    // NOTE: the moves are recorded in memory only; a session's file keeps their summaries.
    let why = match resumed {
        true => format!(
            "{why}; a resumed session has only the turns of this run (those of earlier runs are not kept): \
             calibrate anew to fit the gyro"
        ),
        false => why,
    };
    feedback.say(&format!("gyro: scale and misalignment not calibrated: {why}"));
    outcome.not_fitted = Some(why);
    (*chosen, outcome)
}

/// The gyro's G the session uploaded in an earlier run, when it fitted one.
fn earlier_g(session: &Session) -> Option<shared::linalg::Mat3<f32>> {
    let matrix = session.uploaded.as_ref()?.gyro.matrix;
    (matrix != shared::linalg::identity::<f32>()).then_some(matrix)
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
    let summaries = procedure::turn_summaries(&moves.recorded, session, chosen, &g);
    (!summaries.is_empty()).then_some(summaries)
}

/// The verification turn on the uploaded calibration; `None` (said) when it could not be measured.
pub(super) fn check<P: Port>(
    client: &mut Client<P>,
    hand: &mut dyn Hand,
    rate_hz: u16,
    outcome: &GyroOutcome,
    feedback: &mut dyn Feedback,
) -> Result<Option<TurnCheck>, ProcedureError> {
    // NOTE: a measured turn is shown with the report at the end; only why there is none is said here.
    let result = procedure::check_turn(client, hand, rate_hz, outcome.fit.as_ref(), feedback)?;
    if let Err(why) = &result {
        feedback.say(why);
    }
    Ok(result.ok())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::procedure::Told;

    #[test]
    fn a_resumed_run_without_turns_keeps_an_earlier_upload_s_g_or_says_why_it_has_none() {
        let session = crate::sim::sessions::adaptive(1, 0.0, 0.004);
        let chosen = crate::export::Source::from_session(&session, "s.json").unwrap().calibration;
        let why = || "only 0 usable turns".to_owned();
        let mut told = Told(Vec::new());
        let (none, outcome) = without_fit(why(), true, &session, &chosen, GyroOutcome::default(), &mut told);
        assert_eq!(none.gyro.matrix, chosen.gyro.matrix);
        assert!(outcome.not_fitted.is_some_and(|w| w.contains("a resumed session has only the turns")), "{:?}", told.0);
        let mut uploaded = chosen;
        uploaded.gyro.matrix = [[1.02, 0.0, 0.0], [0.0, 0.98, 0.0], [0.0, 0.0, 1.01]];
        let session = Session { uploaded: Some(uploaded), ..session };
        let (kept, outcome) = without_fit(why(), true, &session, &chosen, GyroOutcome::default(), &mut told);
        assert_eq!(kept.gyro.matrix, uploaded.gyro.matrix);
        assert!(outcome.not_fitted.is_none() && told.0.last().is_some_and(|l| l.contains("G kept")), "{:?}", told.0);
        // A first run has no earlier upload to keep: it says why there is no G.
        let (first, _) = without_fit(why(), false, &session, &chosen, GyroOutcome::default(), &mut told);
        assert_eq!(first.gyro.matrix, chosen.gyro.matrix);
    }
}
