//! What a run resumed from its session keeps and claims: the captures are the session's, but what
//! lived only in the earlier run's memory (the moves the gyro's G was fitted to, the board's clock
//! at its first capture) is not there to use again.

use shared::calibration::GyroCalibration;
use shared::linalg::{identity, Mat3};
use shared::Calibration;

use crate::report::gyro::GyroOutcome;
use crate::session::{Session, SessionKind};

/// The calibration to upload when no G could be fitted to this run's moves (`why`), and the line
/// to tell the person: with the G this session uploaded in an earlier run when it was `resumed`
/// after one; else `chosen` as it is, with why it has no G.
pub fn gyro_without_fit(
    why: String,
    resumed: bool,
    session: &Session,
    chosen: &Calibration,
    mut outcome: GyroOutcome,
) -> (Calibration, GyroOutcome, String) {
    if let (true, Some(matrix)) = (resumed, mutant!("resume-drops-earlier-g", earlier_g(session), None)) {
        let said = "gyro: G kept from the calibration this session uploaded in an earlier run (the moves it was \
                    fitted to are not kept to fit again)";
        return (Calibration { gyro: GyroCalibration { matrix, ..chosen.gyro }, ..*chosen }, outcome, said.into());
    }
    // NOTE: the moves are recorded in memory only; a session's file keeps their summaries.
    let why = match resumed {
        true => format!(
            "{why}; a resumed session has only the turns of this run (those of earlier runs are not kept): \
             calibrate anew to fit the gyro"
        ),
        false => why,
    };
    let said = format!("gyro: scale and misalignment not calibrated: {why}");
    outcome.not_fitted = Some(why);
    (*chosen, outcome, said)
}

/// The gyro's G the session uploaded in an earlier run, when it fitted one.
fn earlier_g(session: &Session) -> Option<Mat3<f32>> {
    let matrix = session.uploaded.as_ref()?.gyro.matrix;
    (matrix != identity::<f32>()).then_some(matrix)
}

/// When the board's time on the bench began, in the board's clock (seconds), as the run may claim
/// it: the first capture's start, unless the run was resumed (that capture was taken in another run,
/// so the board time is unknown).
pub fn board_time_start(first_capture_s: Option<f64>, resumed: bool) -> Option<f64> {
    mutant!("resume-claims-board-time", first_capture_s.filter(|_| !resumed), first_capture_s)
}

/// The session as it is kept once the board holds `uploaded`, before the verification: a Ctrl-C or
/// a pulled cable during the verification still leaves a session that says what the board holds.
pub fn kept_before_verifying(session: &Session, uploaded: Calibration) -> Session {
    Session {
        uploaded: mutant!("kept-before-verifying-without-upload", Some(uploaded), session.uploaded),
        ..session.clone()
    }
}

/// What a resumed session makes of `--chip-fit` (`asked_quick`) and `--seconds` given differently
/// from when it was begun, in words: it goes on as it was begun (its captures, fit and report must
/// agree).
pub fn resumed_as_begun(begun: SessionKind, asked_quick: bool, asked_seconds: Option<u8>) -> Vec<String> {
    let kind = |chip: bool| if chip { "a calibration fitted on the chip" } else { "a full calibration" };
    let begun_quick = begun == SessionKind::Quick;
    let mut lines = Vec::new();
    if asked_quick != begun_quick {
        lines.push(format!(
            "this session was begun as {}; it goes on as one ({} is not used: start a new session for the other)",
            kind(begun_quick),
            if asked_quick { "--chip-fit" } else { "leaving out --chip-fit" }
        ));
    }
    if let (SessionKind::Adaptive, Some(seconds)) = (begun, asked_seconds) {
        lines.push(format!(
            "this session was begun adaptive (each position captured until its mean is known); it goes on so and \
             --seconds {seconds} is not used (start a new session for captures of a fixed length)"
        ));
    }
    lines
}

#[cfg(test)]
mod tests;
