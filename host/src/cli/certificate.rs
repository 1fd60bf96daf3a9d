//! `accelcal certificate`: issue a session's certificate (JSON and a printable page), or check that a
//! certificate file is as it was issued.

use crate::session::SessionFiles;
use std::path::{Path, PathBuf};

use super::args::{CertificateAction, CertificateArgs};
use crate::certificate::{self, Certificate};
use crate::error::Error;
use crate::procedure::Feedback;
use crate::session::{stem_file, stem_of, write_atomically, Session, TargetVerdict};

/// Runs `accelcal certificate`.
pub(super) fn certificate(args: &CertificateArgs) -> Result<(), Error> {
    match &args.action {
        CertificateAction::Issue { session, json, replace } => {
            let loaded = Session::load(session)?;
            for earlier in beside(session) {
                replace.check(&earlier, "it was issued before (`accelcal certificate verify` checks it)")?;
            }
            let issued = issue(&loaded, session)?;
            let (json_path, page) = written(&issued, session)?;
            if *json {
                println!("{}", issued.to_json());
            } else {
                println!("certificate written to {} and {}", json_path.display(), page.display());
            }
            Ok(())
        }
        CertificateAction::Verify { file } => {
            let checked = certificate::check(file)?;
            let serial = checked.board.serial.as_deref().unwrap_or("(no serial)");
            println!("{}: unchanged since it was issued (board {serial}, SHA-256 {})", file.display(), checked.sha256);
            Ok(())
        }
    }
}

/// The certificate of a session, or why it cannot be issued: its captures cannot be fitted, or the
/// session's own verification contradicts the certificate's predicted | |a| - g |.
pub(super) fn issue(session: &Session, path: &Path) -> Result<Certificate, Error> {
    let certificate =
        Certificate::issue(session).map_err(|source| Error::CannotReport { path: path.into(), source })?;
    let predicted_mg = certificate.predicted.norm_error_mg.expanded;
    // NOTE: the verified figure carries its own noise: the error without it must exceed U by more
    // than one noise floor to contradict it (as `Verification::against` judges a target).
    match &certificate.verification {
        Some(v) if v.after_rms_without_noise_mg > predicted_mg + v.noise_floor_mg => Err(Error::Contradicted {
            path: path.into(),
            verified_mg: v.after_rms_without_noise_mg,
            floor_mg: v.noise_floor_mg,
            predicted_mg,
        }),
        _ => Ok(certificate),
    }
}

/// The certificate, or none, said why, when the calibration missed its target by more than its
/// noise or its verification contradicts the certificate's prediction.
pub(super) fn unless_failed(
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
pub(super) fn unless_contradicted(
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
pub(super) fn issue_beside(
    session: &Session,
    path: &Path,
    lot: Option<&Path>,
    feedback: &mut dyn Feedback,
) -> Result<(), Error> {
    let Some(certificate) = unless_contradicted(session, path, feedback)? else {
        return Ok(());
    };
    let (json, _) = written(&certificate, path)?;
    feedback.say(&format!("certificate: {}", json.display()));
    if let Some(lot) = lot {
        feedback.say(&super::lot::add_issued(lot, &certificate)?);
    }
    Ok(())
}

/// Writes a certificate's JSON and page beside the session at `session_path`; their paths.
pub(super) fn written(certificate: &Certificate, session_path: &Path) -> Result<(PathBuf, PathBuf), Error> {
    let [json, page] = beside(session_path);
    write_atomically(&json, certificate.to_json().as_bytes())?;
    write_atomically(&page, certificate::html::page(certificate).as_bytes())?;
    Ok((json, page))
}

/// A session's certificate files: its JSON and its printable page beside it.
fn beside(session_path: &Path) -> [PathBuf; 2] {
    let stem = stem_of(session_path);
    [stem_file(&stem, "certificate.json"), stem_file(&stem, "certificate.html")]
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
