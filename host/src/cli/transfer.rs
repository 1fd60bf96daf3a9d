//! Moving calibrations between a file and the board: `upload`, `download`, `save`, `erase`.

use std::path::Path;

use shared::protocol::CalibrationSlot;

use super::args::Device;
use crate::calibration::{describe, CalibrationJson};
use crate::error::Error;
use crate::export::Source;
use crate::report;
use crate::session::{Session, SessionError};

/// `accelcal upload FILE [--save]`: what `download`, `fit --json` (in g) or `calibrate --json` wrote,
/// or a session (as `export` takes it).
pub(super) fn upload(device: &Device, file: &Path, save: bool) -> Result<(), Error> {
    let text = std::fs::read_to_string(file).map_err(|source| Error::ReadFile { path: file.into(), source })?;
    let record = uploadable(&text, file)?;
    let mut opened = device.open()?;
    let connection = &mut opened.connection;
    let calibration = record.to_device(connection.info.config.range)?;
    connection.client.set_calibration(calibration)?;
    if save {
        connection.client.save_calibration()?;
    }
    let kept = if save { " and saved" } else { " (active until reset; run save to keep it)" };
    println!("uploaded {}{kept}", describe(&calibration));
    Ok(())
}

/// The calibration record in a file: a calibration's JSON, or the calibration a session's captures
/// give, fitted as `calibrate` and `export` fit them (with the gyro's G the session uploaded).
fn uploadable(text: &str, file: &Path) -> Result<CalibrationJson, Error> {
    match serde_json::from_str::<serde_json::Value>(text) {
        Ok(value) if Session::is_session_json(&value) => {
            let not_a_session =
                |e: serde_json::Error| SessionError::NotASession { path: file.into(), reason: e.to_string() };
            let session = Session::from_json(value).map_err(not_a_session)?;
            let source = Source::from_session(&session, &file.display().to_string())?;
            Ok(CalibrationJson::from_device(&source.calibration))
        }
        _ => Ok(CalibrationJson::from_text(text)?),
    }
}

/// `accelcal download [--stored]`: the active (or stored) calibration as JSON.
pub(super) fn download(device: &Device, stored: bool) -> Result<(), Error> {
    let slot = if stored { CalibrationSlot::Stored } else { CalibrationSlot::Active };
    let calibration = device.open()?.connection.client.calibration(slot)?.ok_or(Error::NothingToDownload)?;
    println!("{}", report::json::calibration(&CalibrationJson::from_device(&calibration)));
    Ok(())
}

/// `accelcal save`.
pub(super) fn save(device: &Device) -> Result<(), Error> {
    device.open()?.connection.client.save_calibration()?;
    println!("saved");
    Ok(())
}

/// `accelcal erase`.
pub(super) fn erase(device: &Device) -> Result<(), Error> {
    device.open()?.connection.client.erase_calibration()?;
    println!("stored calibration erased");
    Ok(())
}
