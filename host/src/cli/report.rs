//! `accelcal report SESSION`: a session's report as an HTML page, text or JSON; and the page
//! `calibrate --session` writes beside its session.

use crate::session::SessionFiles;

use super::args::ReportArgs;
use crate::ended::{report_page_path, session_report, write_report_page};
use crate::error::Error;
use crate::report::{self, SessionReport};
use crate::sections;
use crate::session::Session;

/// Reads the session, builds its report, writes the page and prints the text (or the JSON).
pub(super) fn report(args: &ReportArgs) -> Result<(), Error> {
    let report = with_given(args)?;
    if args.json {
        // NOTE: the page first, so that a reader gone from the JSON (`| head`) does not cost it.
        if let Some(path) = &args.output {
            write_report_page(&report, path)?;
        }
        println!("{}", report::json::session_report(&report));
        return Ok(());
    }
    let path = args.output.clone().unwrap_or_else(|| report_page_path(&args.session));
    write_report_page(&report, &path)?;
    print!("{}", report::text::session_report(&report));
    println!("report written to {}", path.display());
    Ok(())
}

/// The session's report with the temperature and noise sections given on the command line.
fn with_given(args: &ReportArgs) -> Result<SessionReport, Error> {
    let session = Session::load(&args.session)?;
    let mut report = session_report(&session, &args.session)?;
    let serial = session.board.as_ref().map(|b| b.serial.as_str());
    if let Some(path) = &args.thermal {
        let (section, plot) = sections::temperature(path, serial)?;
        report = report.with_temperature(section, plot);
    }
    if let Some(path) = &args.noise {
        let (section, plot) = sections::allan(path, serial)?;
        report = report.with_allan_deviation(section, plot);
    }
    Ok(report)
}
