//! `accelcal certificate`: issue a session's certificate (JSON and a printable page), or check that a
//! certificate file is as it was issued.

use crate::session::SessionFiles;

use super::args::{CertificateAction, CertificateArgs};
use crate::certificate;
use crate::ended::{certificate_paths, issue, write_certificate};
use crate::error::Error;
use crate::session::Session;

/// Runs `accelcal certificate`.
pub(super) fn certificate(args: &CertificateArgs) -> Result<(), Error> {
    match &args.action {
        CertificateAction::Issue { session, json, replace } => {
            let loaded = Session::load(session)?;
            for earlier in certificate_paths(session) {
                replace.check(&earlier, "it was issued before (`accelcal certificate verify` checks it)")?;
            }
            let issued = issue(&loaded, session)?;
            let (json_path, page) = write_certificate(&issued, session)?;
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
