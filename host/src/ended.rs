//! What a session leaves when its run ends. Verified: its certificate (withheld, said why, when the
//! calibration missed its target or its verification contradicts the prediction), the printable
//! report page, and the certificate's row in a lot; a board's run and a stream's run end here alike.
//! Stopped: the command that goes on with it, when it holds a capture.

use std::path::{Path, PathBuf};

use crate::certificate::{self, Certificate};
use crate::error::Error;
use crate::lot::Lot;
use crate::procedure::{Feedback, ProcedureError};
use crate::report::SessionReport;
use crate::session::{stem_file, stem_of, write_atomically, Session, SessionFiles, TargetVerdict};

/// The certificate of a session, or why it cannot be issued: its captures cannot be fitted, or the
/// session's own verification contradicts the certificate's predicted | |a| - g |.
pub fn issue(session: &Session, path: &Path) -> Result<Certificate, Error> {
    let certificate =
        Certificate::issue(session).map_err(|source| Error::CannotReport { path: path.into(), source })?;
    let predicted_mg = certificate.predicted.norm_error_mg.expanded;
    match certificate.contradicting_verification() {
        Some(v) => Err(Error::Contradicted {
            path: path.into(),
            verified_mg: v.after_rms_without_noise_mg,
            floor_mg: v.noise_floor_mg,
            predicted_mg,
        }),
        None => Ok(certificate),
    }
}

/// The certificate, or none, said why, when the calibration missed its target by more than its
/// noise or its verification contradicts the certificate's prediction.
pub fn unless_failed(
    verified: &Session,
    target: &TargetVerdict,
    path: &Path,
    feedback: &mut dyn Feedback,
) -> Result<Option<Certificate>, Error> {
    if target.missed {
        feedback.say("no certificate: the calibration missed its target by more than its noise (see the verdict)");
        return Ok(None);
    }
    unless_contradicted(verified, path, feedback)
}

/// The certificate, or none, said why, when the session's verification contradicts the
/// certificate's predicted | |a| - g |.
pub fn unless_contradicted(
    verified: &Session,
    path: &Path,
    feedback: &mut dyn Feedback,
) -> Result<Option<Certificate>, Error> {
    match issue(verified, path) {
        Ok(certificate) => Ok(Some(certificate)),
        Err(contradicted @ Error::Contradicted { .. }) => {
            feedback.say(&contradicted.to_string());
            Ok(None)
        }
        Err(e) => Err(e),
    }
}

/// Issues a session's certificate beside it (at `path`), and adds it to the `lot` when one is given,
/// unless its verification contradicts the certificate's prediction (said why).
pub fn issue_beside(
    session: &Session,
    path: &Path,
    lot: Option<&Path>,
    feedback: &mut dyn Feedback,
) -> Result<(), Error> {
    let Some(certificate) = unless_contradicted(session, path, feedback)? else {
        return Ok(());
    };
    let (json, _) = write_certificate(&certificate, path)?;
    feedback.say(&format!("certificate: {}", json.display()));
    if let Some(lot) = lot {
        feedback.say(&Lot::add_issued(lot, &certificate)?);
    }
    Ok(())
}

/// A verified board session kept at `stem` (when it is kept): saved, its report and certificate
/// written beside it, and the certificate added to the `lot` when one is given. `not_kept` names
/// a failed save with the way on.
pub fn keep_verified(
    verified: &Session,
    certificate: Option<&Certificate>,
    (stem, lot): (Option<&Path>, Option<&Path>),
    not_kept: impl FnOnce(crate::session::SessionError) -> Error,
    feedback: &mut dyn Feedback,
) -> Result<(), Error> {
    if let Some(stem) = stem {
        verified.save(stem).map_err(not_kept)?;
        keep_with_report(verified, certificate, stem, feedback)?;
    }
    if let (Some(lot), Some(certificate)) = (lot, certificate) {
        feedback.say(&Lot::add_issued(lot, certificate)?);
    }
    Ok(())
}

/// Writes the verified session's report and certificate beside it, and says where.
fn keep_with_report(
    session: &Session,
    certificate: Option<&Certificate>,
    stem: &Path,
    feedback: &mut dyn Feedback,
) -> Result<(), Error> {
    let json = stem_file(stem, "json");
    let page = report_page_path(&json);
    write_report_page(&session_report(session, &json)?, &page)?;
    let certificate = match certificate {
        Some(certificate) => format!("; certificate to {}", write_certificate(certificate, &json)?.0.display()),
        None => String::new(),
    };
    feedback.say(&format!("session kept in {}; report written to {}{certificate}", json.display(), page.display()));
    Ok(())
}

/// Writes a certificate's JSON and page beside the session at `session_path`; their paths.
pub fn write_certificate(certificate: &Certificate, session_path: &Path) -> Result<(PathBuf, PathBuf), Error> {
    let [json, page] = certificate_paths(session_path);
    write_atomically(&json, certificate.to_json().as_bytes())?;
    write_atomically(&page, certificate::html::page(certificate).as_bytes())?;
    Ok((json, page))
}

/// A session's certificate files: its JSON and its printable page beside it.
pub fn certificate_paths(session_path: &Path) -> [PathBuf; 2] {
    let stem = stem_of(session_path);
    [stem_file(&stem, "certificate.json"), stem_file(&stem, "certificate.html")]
}

/// The report of the session at `path`.
pub fn session_report(session: &Session, path: &Path) -> Result<SessionReport, Error> {
    SessionReport::new(session).map_err(|source| Error::CannotReport { path: path.into(), source })
}

/// Writes the report's HTML page to `path`.
pub fn write_report_page(report: &SessionReport, path: &Path) -> Result<(), Error> {
    let page = crate::report::html::page(report)?;
    Ok(write_atomically(path, page.as_bytes())?)
}

/// The page's default place: the session's path with `.html`.
pub fn report_page_path(session: &Path) -> PathBuf {
    session.with_extension("html")
}

/// Why a run stopped, with the command that resumes its session (on the board `device` names)
/// when the session file holds a capture.
pub fn stopped(source: ProcedureError, kept_at: Option<&Path>, device: String) -> Error {
    match kept_at.map(kept_on_disk) {
        Some((path, captures)) if captures > 0 => Error::Stopped { source: Box::new(source), captures, path, device },
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

/// What a person who just calibrated one board is told last: that the board was simulated and
/// where its session went (nowhere, unless `kept`), and what to run next.
pub fn what_next(simulated: bool, kept: bool) -> Vec<String> {
    let mut lines = Vec::new();
    if simulated && !kept {
        lines.push(
            "this was a simulated board (the firmware's own code on a simulated MPU-6050): nothing was kept; add \
             --session NAME to keep its session, report page and certificate"
                .to_owned(),
        );
    }
    lines.push(
        match simulated {
            true => {
                "next: with your board plugged in, `accelcal calibrate --port PORT` (`accelcal ports` lists the ports)"
            }
            false => {
                "next: the board applies this calibration to every sample; for your own code, `accelcal export \
                  SESSION.json --to c` (or another --to) writes it there"
            }
        }
        .to_owned(),
    );
    lines
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::session::Verification;

    #[test]
    fn no_certificate_is_issued_where_the_session_s_verification_contradicts_its_prediction() {
        let path = Path::new("s1.json");
        let session = crate::sim::sessions::adaptive(1, 0.5, 0.004);
        let predicted_mg = issue(&session, path).unwrap().predicted.norm_error_mg.expanded;
        let verified = |error_mg: f64| {
            let floor_mg = 0.15;
            let rms_mg = (error_mg.powi(2) + floor_mg * floor_mg).sqrt();
            Session { verification: Some(Verification::example(rms_mg, floor_mg)), ..session.clone() }
        };
        // Within U and its noise: issued.
        assert!(issue(&verified(predicted_mg + 0.14), path).is_ok(), "U {predicted_mg:.3} mg");
        let error = issue(&verified(predicted_mg + 0.16), path).unwrap_err();
        assert!(matches!(error, Error::Contradicted { .. }), "{error}");
        let said = format!("found {:.3} mg", predicted_mg + 0.16);
        assert!(error.to_string().contains(&said), "{error}");
    }

    #[test]
    fn calibrate_issues_no_certificate_for_a_calibration_that_missed_its_target_by_more_than_its_noise() {
        let path = Path::new("s1.json");
        let verification = Verification::example(0.40, 0.15);
        let session =
            Session { verification: Some(verification.clone()), ..crate::sim::sessions::adaptive(1, 0.5, 0.004) };
        let mut feedback = crate::procedure::Silent { yes: true };
        // 0.37 mg without its noise: within 0.5 mg and 0.3 mg + its noise; beyond 0.2 mg + its noise.
        for (target_mg, certified) in [(0.5, true), (0.3, true), (0.2, false)] {
            let target = verification.against(Some(target_mg));
            let issued = unless_failed(&session, &target, path, &mut feedback).unwrap();
            assert_eq!(issued.is_some(), certified, "target {target_mg} mg: {}", target.line);
        }
    }
}
