//! `accelcal certificate`: issue a session's certificate (JSON and a printable page), or check that a
//! certificate file is as it was issued.

use std::path::{Path, PathBuf};

use clap::{Args, Subcommand};

use crate::certificate::{self, Certificate};
use crate::error::Error;
use crate::session::{stem_file, stem_of, write_atomically, Session};

/// `accelcal certificate`.
#[derive(Args)]
pub struct CertificateArgs {
    #[command(subcommand)]
    pub action: CertificateAction,
}

/// What to do with a certificate.
#[derive(Subcommand)]
pub enum CertificateAction {
    /// Issues the certificate of a session (PATH.certificate.json and PATH.certificate.html beside it).
    Issue {
        /// The session file (PATH.json written by calibrate --session).
        session: PathBuf,
        /// Print the certificate as JSON too.
        #[arg(long)]
        json: bool,
    },
    /// Checks that a certificate file is unchanged since it was issued (its SHA-256).
    Verify {
        /// The certificate's .json file.
        file: PathBuf,
    },
}

/// Runs `accelcal certificate`.
pub(super) fn certificate(args: &CertificateArgs) -> Result<(), Error> {
    match &args.action {
        CertificateAction::Issue { session, json } => {
            let loaded = Session::load(session)?;
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

/// The certificate of a session, or why it cannot be issued.
pub(super) fn issue(session: &Session, path: &Path) -> Result<Certificate, Error> {
    Certificate::issue(session).map_err(|source| Error::CannotReport { path: path.into(), source })
}

/// Writes a certificate's JSON and page beside the session at `session_path`; their paths.
pub(super) fn written(certificate: &Certificate, session_path: &Path) -> Result<(PathBuf, PathBuf), Error> {
    let stem = stem_of(session_path);
    let json = stem_file(&stem, "certificate.json");
    let page = stem_file(&stem, "certificate.html");
    write_atomically(&json, certificate.to_json().as_bytes())?;
    write_atomically(&page, certificate::html::page(certificate).as_bytes())?;
    Ok((json, page))
}
