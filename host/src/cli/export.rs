//! `accelcal export`: the calibration in the format of another program (host/src/export).

use std::io::Write;
use std::path::Path;

use shared::protocol::CalibrationSlot;

use super::args::{Device, ExportArgs};
use crate::error::Error;
use crate::export::{self, Noise, Readings, Source, Target};
use crate::session::{write_atomically, BoardRecord};

/// Reads the calibration, exports it, writes the file (or stdout) and says what it carries.
pub(super) fn export(args: &ExportArgs) -> Result<(), Error> {
    if export_is_binary(args.to) && args.output.is_none() {
        return Err(export::ExportError::BinaryNeedsFile { target: target_name(args.to) }.into());
    }
    if let Some(path) = &args.output {
        args.replace.check(path, "give another -o")?;
    }
    let mut source = match &args.calibration {
        Some(path) => Source::from_text(&read(path)?, &path.display().to_string())?,
        None => from_board(&args.device)?,
    };
    if let Some(path) = &args.noise {
        source.noise = Some(Noise::from_text(&read(path)?)?);
    }
    let exported = export::export(&source, args.to)?;
    match &args.output {
        Some(path) => {
            write_atomically(path, &exported.bytes)?;
            eprintln!("{}\nwrote {}", shown(&exported), path.display());
        }
        None => {
            std::io::stdout()
                .write_all(&exported.bytes)
                .map_err(|source| Error::WriteFile { path: "stdout".into(), source })?;
        }
    }
    Ok(())
}

/// What the terminal shows beside a written file: all of a binary file's statement, else what the
/// file carries and loses (the rest is in the file).
fn shown(exported: &export::Export) -> String {
    let wanted = |line: &&String| exported.binary || line.starts_with("carries:") || line.starts_with("lost");
    exported.statement.iter().filter(wanted).cloned().collect::<Vec<_>>().join("\n")
}

/// The board's active calibration and its serial number.
fn from_board(device: &Device) -> Result<Source, Error> {
    let mut opened = device.open()?;
    let connection = &mut opened.connection;
    let board = BoardRecord::of(&connection.info);
    let calibration = connection.client.calibration(CalibrationSlot::Active)?.ok_or(Error::NothingToDownload)?;
    let from =
        device.port.clone().map_or_else(|| "the simulated board (--sim)".to_owned(), |p| format!("the board on {p}"));
    let readings = Readings::board(board.sensor, calibration.mean_temp_c);
    Ok(Source { calibration, serial: Some(board.serial), from, noise: None, readings })
}

fn read(path: &Path) -> Result<String, Error> {
    std::fs::read_to_string(path).map_err(|source| Error::ReadFile { path: path.into(), source })
}

fn export_is_binary(target: Target) -> bool {
    target == Target::AdafruitEeprom
}

/// The name `--to` takes for `target`.
fn target_name(target: Target) -> String {
    <&'static str>::from(target).to_owned()
}
