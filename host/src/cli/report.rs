//! `accelcal report SESSION`: a session's report as an HTML page, text or JSON; and the page
//! `calibrate --session` writes beside its session.

use crate::session::SessionFiles;
use std::path::{Path, PathBuf};

use super::args::ReportArgs;
use crate::error::Error;
use crate::noise;
use crate::report::allan::AllanSection;
use crate::report::temperature::TemperatureSection;
use crate::report::thermal::ThermalReport;
use crate::report::{self, SessionReport};
use crate::session::{write_atomically, Session};

/// Reads the session, builds its report, writes the page and prints the text (or the JSON).
pub(super) fn report(args: &ReportArgs) -> Result<(), Error> {
    let report = with_given(args)?;
    if args.json {
        // NOTE: the page first, so that a reader gone from the JSON (`| head`) does not cost it.
        if let Some(path) = &args.output {
            write_page(&report, path)?;
        }
        println!("{}", report::json::session_report(&report));
        return Ok(());
    }
    let path = args.output.clone().unwrap_or_else(|| beside(&args.session));
    write_page(&report, &path)?;
    print!("{}", report::text::session_report(&report));
    println!("report written to {}", path.display());
    Ok(())
}

/// The session's report with the temperature and noise sections given on the command line.
fn with_given(args: &ReportArgs) -> Result<SessionReport, Error> {
    let session = Session::load(&args.session)?;
    let mut report = build(&session, &args.session)?;
    let serial = session.board.as_ref().map(|b| b.serial.as_str());
    if let Some(path) = &args.thermal {
        let (section, plot) = thermal_section(path, serial)?;
        report = report.with_temperature(section, plot);
    }
    if let Some(path) = &args.noise {
        let (section, plot) = noise_section(path, serial)?;
        report = report.with_allan_deviation(section, plot);
    }
    Ok(report)
}

/// The temperature section from the output of `accelcal thermal --json` at `path`, refused when it
/// was learned on another board than the session's (`serial`).
fn thermal_section(path: &Path, serial: Option<&str>) -> Result<(TemperatureSection, report::Figure), Error> {
    let refused = |reason: String| Error::ReportInput { path: path.into(), reason };
    let text = std::fs::read_to_string(path).map_err(|source| Error::ReadFile { path: path.into(), source })?;
    let thermal: ThermalReport =
        serde_json::from_str(&text).map_err(|e| refused(format!("{e}; give the output of accelcal thermal --json")))?;
    same_board(path, ("learned", "thermal JSON"), thermal.serial.as_deref(), serial).map_err(refused)?;
    TemperatureSection::new(&thermal).map_err(refused)
}

/// The Allan deviation section from the output of `accelcal noise --json` at `path`, or from the
/// recording there (analysed as `accelcal noise` would), refused when it was recorded on another
/// board than the session's (`serial`).
fn noise_section(path: &Path, serial: Option<&str>) -> Result<(AllanSection, report::Figure), Error> {
    let refused = |reason: String| Error::ReportInput { path: path.into(), reason };
    let bytes = std::fs::read(path).map_err(|source| Error::ReadFile { path: path.into(), source })?;
    let json = if bytes.trim_ascii_start().starts_with(b"{") {
        noise::json::read(&String::from_utf8_lossy(&bytes)).map_err(refused)?
    } else {
        noise::json::NoiseJson::of(&noise::analyse(&noise::input::read_path(path, None)?))
    };
    same_board(path, ("recorded", "recording"), json.serial.as_deref(), serial).map_err(refused)?;
    AllanSection::new(&json).map_err(refused)
}

/// Whether the file at `path`, `(done, what)` on the board `file_board`, is of the session's board
/// `session_board`: another board's is refused; a file naming no board is read with a note saying so.
fn same_board(
    path: &Path,
    (done, what): (&str, &str),
    file_board: Option<&str>,
    session_board: Option<&str>,
) -> Result<(), String> {
    match (file_board, session_board) {
        (Some(file), Some(session)) if file != session => Err(format!(
            "it was {done} on board {file}, the session was taken on board {session}: give the {what} of the \
             session's board"
        )),
        (None, _) => {
            eprintln!(
                "note: {} names no board (written before accelcal recorded the serial): that it is this session's \
                 board is not checked",
                path.display()
            );
            Ok(())
        }
        _ => Ok(()),
    }
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
