//! A board described as `accelcal info` shows it: its serial, firmware and protocol, its part and
//! the family its offset registers confirm, its range and rate, its active and stored
//! calibrations, and on request its registers; as text for a person or as JSON.

use serde::Serialize;
use shared::protocol::{DeviceInfo, SensorIdentity};
use shared::Calibration;

use super::check::{check_family, FamilyCheck, FamilyCheckJson};
use super::offsets::OffsetCheckError;
use super::{describe, format_dump, part_name};
use crate::calibration::{describe as describe_calibration, CalibrationJson};
use crate::link::{explain, Client, Port};
use crate::session::BoardRecord;

/// What `info` found on a board.
pub struct BoardInfo<'a> {
    pub info: &'a DeviceInfo,
    pub active: Option<Calibration>,
    pub stored: Option<Calibration>,
    pub family: FamilyOutcome,
    /// Registers 0x00-0x7F with `--registers` (`None` where not read).
    pub registers: Option<Vec<Option<u8>>>,
}

/// The family check as `info` reports it: the check (`None` with no sensor), or why it could not
/// measure.
pub struct FamilyOutcome {
    pub check: Option<FamilyCheck>,
    pub unmeasured: Option<String>,
}

impl FamilyOutcome {
    /// The `family:` line, when there is one.
    fn line(&self) -> Option<String> {
        let why = self.unmeasured.as_ref().map(|why| format!("not checked: {why}"));
        self.check.as_ref().map(FamilyCheck::summary).or(why)
    }
}

/// The offset-register check of the board's sensor; `None` with no sensor. Give the client the
/// Ctrl-C flag first: the check restores its registers after Ctrl-C too.
pub fn family_check<P: Port>(
    client: &mut Client<P>,
    info: &DeviceInfo,
) -> Result<Option<FamilyCheck>, OffsetCheckError> {
    let Ok(sensor) = info.sensor else {
        return Ok(None);
    };
    Ok(Some(check_family(client, &sensor, info.config)?))
}

/// The family check for `info`: the check, or why it could not measure when it left the offset
/// registers as it found them (the rest of `info` stands then); any other failure ends `info`.
pub fn family_check_for_info<P: Port>(
    client: &mut Client<P>,
    info: &DeviceInfo,
) -> Result<FamilyOutcome, OffsetCheckError> {
    match family_check(client, info) {
        Ok(check) => Ok(FamilyOutcome { check, unmeasured: None }),
        Err(error) if error.left_registers_as_found() => {
            Ok(FamilyOutcome { check: None, unmeasured: Some(error.to_string()) })
        }
        Err(error) => Err(error),
    }
}

/// What `accelcal info --json` prints.
#[derive(Serialize)]
struct InfoJson {
    /// The board's serial number, 24 hexadecimal digits (as `ports` and sessions show it).
    serial: String,
    protocol_version: u8,
    firmware: String,
    /// The part's name ("unknown" for a WHO_AM_I of no known part); null with no sensor.
    part: Option<&'static str>,
    /// The WHO_AM_I value; null with no sensor.
    who_am_i: Option<u8>,
    sensor: SensorJson,
    /// What confirmed the family the board runs the part as ("offset registers"); null when nothing
    /// did (see `family_check`) or with no sensor.
    family_confirmed_by: Option<&'static str>,
    /// The offset-register check of the family; null with no sensor or when it could not measure.
    family_check: Option<FamilyCheckJson>,
    /// Why the family check could not measure (the rest of `info` stands); absent when it could.
    #[serde(skip_serializing_if = "Option::is_none")]
    family_check_error: Option<String>,
    range_g: u8,
    sample_rate_hz: u16,
    active: Option<CalibrationJson>,
    stored: Option<CalibrationJson>,
    /// With `--registers`: registers 0x00-0x7F, null where not read (FIFO_R_W, 0x74); absent without.
    #[serde(skip_serializing_if = "Option::is_none")]
    registers: Option<Vec<Option<u8>>>,
}

/// The sensor the board found, or why it found none.
#[derive(Serialize)]
#[serde(untagged)]
enum SensorJson {
    Found(SensorIdentity),
    Missing { error: String },
}

impl BoardInfo<'_> {
    /// The JSON `info --json` prints.
    pub fn json(&self) -> String {
        let (info, family) = (self.info, &self.family);
        let json = InfoJson {
            serial: BoardRecord::of(info).serial,
            protocol_version: info.protocol_version,
            firmware: firmware_version(info),
            part: info.sensor.as_ref().ok().map(part_name),
            who_am_i: info.sensor.as_ref().ok().map(|s| s.who_am_i),
            sensor: info.sensor.map_or_else(|e| SensorJson::Missing { error: explain(&e) }, SensorJson::Found),
            family_confirmed_by: family.check.as_ref().and_then(FamilyCheck::confirmed_by),
            family_check: family.check.as_ref().map(FamilyCheckJson::of),
            family_check_error: family.unmeasured.clone(),
            range_g: info.config.range.full_scale_g(),
            sample_rate_hz: info.config.sample_rate_hz,
            active: self.active.as_ref().map(CalibrationJson::from_device),
            stored: self.stored.as_ref().map(CalibrationJson::from_device),
            registers: self.registers.clone(),
        };
        serde_json::to_string_pretty(&json).unwrap_or_default()
    }

    /// The text `info` prints, with the register dump after it when one was read.
    pub fn text(&self) -> String {
        let info = self.info;
        let serial = BoardRecord::of(info).serial;
        let mut out =
            format!("board serial {serial}, firmware {}, protocol {}\n", firmware_version(info), info.protocol_version);
        out += &match info.sensor {
            Ok(s) => format!("sensor: {}\n", describe(&s)),
            Err(e) => format!("sensor: {}\n", explain(&e)),
        };
        if let Some(line) = self.family.line() {
            out += &format!("family: {line}\n");
        }
        out += &format!("range +-{} g, {} Hz\n", info.config.range.full_scale_g(), info.config.sample_rate_hz);
        let shown =
            |calibration: &Option<Calibration>| calibration.as_ref().map_or("none".to_owned(), describe_calibration);
        out += &format!("active calibration: {}\nstored calibration: {}\n", shown(&self.active), shown(&self.stored));
        if let Some(dump) = &self.registers {
            out += &format!("\n{}", format_dump(&dump_heading(info), dump));
        }
        out
    }
}

/// The first line of a register dump: what a person reporting an unknown part is asked for.
fn dump_heading(info: &DeviceInfo) -> String {
    let sensor = info.sensor.map_or_else(|e| explain(&e), |s| describe(&s));
    format!("accelcal {} register dump, firmware {}: {sensor}", env!("CARGO_PKG_VERSION"), firmware_version(info))
}

fn firmware_version(info: &DeviceInfo) -> String {
    let f = info.firmware;
    format!("{}.{}.{}", f.major, f.minor, f.patch)
}
