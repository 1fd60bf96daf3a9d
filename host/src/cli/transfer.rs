//! Moving calibrations between a file and the board: `upload`, `download`, `save`, `erase`.

use std::path::Path;

use shared::protocol::CalibrationSlot;

use super::args::Device;
use crate::calibration::{describe, CalibrationJson};
use crate::error::Error;
use crate::report;

/// `accelcal upload FILE [--save]`: what `download`, `fit --json` (in g) or `calibrate --json` wrote.
pub(super) fn upload(device: &Device, file: &Path, save: bool) -> Result<(), Error> {
    let text = std::fs::read_to_string(file).map_err(|source| Error::ReadFile { path: file.into(), source })?;
    let record = CalibrationJson::from_text(&text)?;
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
