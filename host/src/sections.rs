//! A session report's sections read from what other commands wrote: the temperature model
//! (`accelcal thermal --json`) and the Allan deviation (`accelcal noise --json`, or the recording
//! itself), each refused when it was taken on another board than the session's.

use std::path::Path;

use crate::error::Error;
use crate::noise;
use crate::report::allan::AllanSection;
use crate::report::temperature::TemperatureSection;
use crate::report::thermal::ThermalReport;
use crate::report::Figure;

/// The temperature section from the output of `accelcal thermal --json` at `path`, refused when it
/// was learned on another board than the session's (`serial`).
pub fn temperature(path: &Path, serial: Option<&str>) -> Result<(TemperatureSection, Figure), Error> {
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
pub fn allan(path: &Path, serial: Option<&str>) -> Result<(AllanSection, Figure), Error> {
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
