//! From the moves of a calibration to the gyro fit: each move's poses seen through the chosen
//! accelerometer calibration (the up directions the turn must carry onto each other) and the gyro
//! bias measured at rest at each of them (re-estimated at every pose, since it drifts).

use shared::Calibration;

use super::RecordedMove;
use crate::fit::gyro::{fit_gyro, summarise_turn, GyroFit, GyroFitError, Turn, TurnSummary};
use crate::session::Session;

/// The turns of `moves`, their poses taken from `session` and corrected by `calibration`.
pub fn turns_of(moves: &[RecordedMove], session: &Session, calibration: &Calibration) -> Vec<Turn> {
    moves.iter().filter_map(|m| turn_of(m, session, calibration)).collect()
}

fn turn_of(recorded: &RecordedMove, session: &Session, calibration: &Calibration) -> Option<Turn> {
    let [before, after] = [recorded.from, recorded.to].map(|i| session.captures.get(i).map(|c| c.stats));
    let (before, after) = (before?, after?);
    let up = |s: &shared::protocol::CaptureStats| unit(calibration.apply_at(s.mean_g, s.temp_c));
    Some(Turn {
        rates_dps: recorded.rates_dps.clone(),
        interval_s: recorded.interval_s,
        bias_before_dps: before.gyro_mean_dps.map(f64::from),
        bias_after_dps: after.gyro_mean_dps.map(f64::from),
        up_before: up(&before),
        up_after: up(&after),
    })
}

fn unit(v: [f32; 3]) -> [f64; 3] {
    let v = v.map(f64::from);
    let n = shared::linalg::norm(v);
    v.map(|x| x / n)
}

/// The gyro fit of a calibration's moves, or why there is none (naming the turns to add).
pub fn fit_moves(
    moves: &[RecordedMove],
    session: &Session,
    calibration: &Calibration,
) -> Result<GyroFit, GyroFitError> {
    fit_gyro(&turns_of(moves, session, calibration))
}

/// Each move's turn as the report shows it, calibrated with `g` (the identity when G was not
/// fitted), its positions named as captured.
pub fn turn_summaries(
    moves: &[RecordedMove],
    session: &Session,
    calibration: &Calibration,
    g: &shared::linalg::Mat3<f64>,
) -> Vec<TurnSummary> {
    let name = |i: usize| session.captures.get(i).map_or("?", |c| c.name.as_str());
    let summary =
        |m: &RecordedMove| turn_of(m, session, calibration).map(|t| summarise_turn(&t, g, name(m.from), name(m.to)));
    moves.iter().filter_map(summary).collect()
}
