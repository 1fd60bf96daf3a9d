//! The board itself: `ports`, `info`, `stream`.

use shared::protocol::{CalibrationSlot, StreamKind};

use super::args::{Device, StreamArgs};
use crate::error::Error;
use crate::link::{ask, is_worth_asking, serial_ports, StreamRequest};
use crate::part::info::{family_check_for_info, BoardInfo};
use crate::part::register_dump;
use crate::recording::csv::{sample_cells, stream_csv_columns, write_row};
use crate::session::BoardRecord;

/// `accelcal ports`: serial ports, ours marked; a USB port of another identity is asked (listened to
/// first, then greeted) whether an accelcal board is behind it.
pub(super) fn ports() -> Result<(), Error> {
    let ports = serial_ports()?;
    if ports.is_empty() {
        println!("no serial ports found; is the board plugged in?");
    }
    for port in ports {
        let serial = port.serial.as_ref().map_or(String::new(), |s| format!("  serial {s}"));
        let behind = if port.is_accelcal {
            "  <- accelcal board".to_owned()
        } else if is_worth_asking(&port) {
            super::device::asking(&port);
            ask(&port.path).shown()
        } else {
            String::new()
        };
        println!("{}{serial}{behind}", port.path);
    }
    Ok(())
}

/// `accelcal info [--json] [--registers]`.
pub(super) fn info(device: &Device, json: bool, registers: bool) -> Result<(), Error> {
    let mut opened = device.open()?;
    let client = &mut opened.connection.client;
    let active = client.calibration(CalibrationSlot::Active)?;
    let stored = client.calibration(CalibrationSlot::Stored)?;
    let registers = if registers { Some(register_dump(client)?) } else { None };
    let info = &opened.connection.info;
    client.interrupt_on(crate::terminal::interrupt_on_ctrl_c());
    let family = family_check_for_info(client, info)?;
    let shown = BoardInfo { info, active, stored, family, registers };
    match json {
        true => println!("{}", shown.json()),
        false => print!("{}", shown.text()),
    }
    Ok(())
}

/// `accelcal stream`: samples as CSV on stdout; fails naming the loss when any sample was lost.
/// A reader that goes away (`| head`) ends the stream on the board and the command quietly.
pub(super) fn stream(args: &StreamArgs) -> Result<(), Error> {
    let mut opened = args.device.open()?;
    if args.calibrated && opened.connection.client.calibration(CalibrationSlot::Active)?.is_none() {
        return Err(Error::NothingToApply);
    }
    let kind = if args.calibrated { StreamKind::Calibrated } else { StreamKind::Raw };
    let request = StreamRequest { kind, rate_hz: args.rate, count: args.count };
    let mut out = csv::Writer::from_writer(std::io::stdout().lock());
    let serial = BoardRecord::of(&opened.connection.info).serial;
    let mut reading = write_row(&mut out, stream_csv_columns()).is_ok();
    let tally = opened.connection.client.stream_while(request, |sample| {
        reading = reading && write_row(&mut out, sample_cells(sample, &serial)).is_ok();
        reading
    })?;
    if reading && out.flush().is_ok() {
        tally.complete()?;
    }
    Ok(())
}
