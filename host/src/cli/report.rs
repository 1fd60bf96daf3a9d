//! `accelcal report SESSION`: a session's report as an HTML page, text or JSON; and the page
//! `calibrate --session` writes beside its session.

use std::path::{Path, PathBuf};

use super::args::ReportArgs;
use crate::error::Error;
use crate::report::{self, SessionReport};
use crate::session::{write_atomically, Session};

/// Reads the session, builds its report, writes the page and prints the text (or the JSON).
pub(super) fn report(args: &ReportArgs) -> Result<(), Error> {
    let session = Session::load(&args.session)?;
    let report = build(&session, &args.session)?;
    if args.json {
        println!("{}", report::json::session_report(&report));
        if let Some(path) = &args.output {
            write_page(&report, path)?;
        }
        return Ok(());
    }
    let path = args.output.clone().unwrap_or_else(|| beside(&args.session));
    write_page(&report, &path)?;
    print!("{}", report::text::session_report(&report));
    println!("report written to {}", path.display());
    Ok(())
}

/// The report of the session at `path`.
pub(super) fn build(session: &Session, path: &Path) -> Result<SessionReport, Error> {
    SessionReport::new(session).map_err(|source| Error::CannotReport { path: path.into(), source })
}

/// Writes the report's HTML page to `path`.
pub(super) fn write_page(report: &SessionReport, path: &Path) -> Result<(), Error> {
    let page = report::html::page(report)?;
    Ok(write_atomically(path, page.as_bytes())?)
}

/// The page's default place: the session's path with `.html`.
pub(super) fn beside(session: &Path) -> PathBuf {
    session.with_extension("html")
}
