//! The board itself: `ports`, `info`, `stream`.

use std::io::Write;

use serde::Serialize;
use shared::protocol::{CalibrationSlot, DeviceInfo, Sample, SensorIdentity, StreamKind};
use shared::Calibration;

use super::args::{Device, StreamArgs};
use crate::calibration::{describe, CalibrationJson};
use crate::error::Error;
use crate::link::{ask, explain, is_worth_asking, serial_ports, Answer, LinkError, StreamRequest};
use crate::link::{Client, Port};
use crate::part::check::{check_family, FamilyCheck, FamilyCheckJson};
use crate::part::{describe as describe_part, format_dump, part_name, register_dump};
use crate::recording::stream_csv_columns;
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
            answered(ask(&port.path))
        } else {
            String::new()
        };
        println!("{}{serial}{behind}", port.path);
    }
    Ok(())
}

/// What `ports` shows after a port of another USB identity: the board found by its handshake, or
/// what it is not.
fn answered(answer: Answer) -> String {
    match answer {
        Answer::Board(connection) => {
            format!(
                "  <- accelcal board (found by its handshake), board serial {}",
                BoardRecord::of(&connection.info).serial
            )
        }
        Answer::Talks(heard) => format!("  (prints on its own: {heard}; nothing was written to it)"),
        Answer::NoBoard(LinkError::Silent { .. }) => "  (no accelcal board: silent, and no answer to its hello)".into(),
        Answer::NoBoard(error) => format!("  (not an accelcal board, or not reachable: {error})"),
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

/// `accelcal info [--json] [--registers]`.
pub(super) fn info(device: &Device, json: bool, registers: bool) -> Result<(), Error> {
    let mut opened = device.open()?;
    let client = &mut opened.connection.client;
    let active = client.calibration(CalibrationSlot::Active)?;
    let stored = client.calibration(CalibrationSlot::Stored)?;
    let dump = if registers { Some(register_dump(client)?) } else { None };
    let info = &opened.connection.info;
    client.interrupt_on(super::terminal::interrupt_on_ctrl_c());
    let family = family_check_for_info(client, info)?;
    if json {
        let output = InfoJson { registers: dump, ..info_json(info, active.as_ref(), stored.as_ref(), family) };
        println!("{}", serde_json::to_string_pretty(&output).unwrap_or_default());
    } else {
        print_info(info, active.as_ref(), stored.as_ref(), &family);
        if let Some(dump) = dump {
            print!("\n{}", format_dump(&dump_heading(info), &dump));
        }
    }
    Ok(())
}

/// The offset-register check of the board's sensor; `None` with no sensor. Give the client the Ctrl-C
/// flag first: the check restores its registers after Ctrl-C too.
pub(super) fn family_check<P: Port>(client: &mut Client<P>, info: &DeviceInfo) -> Result<Option<FamilyCheck>, Error> {
    let Ok(sensor) = info.sensor else {
        return Ok(None);
    };
    Ok(Some(check_family(client, &sensor, info.config)?))
}

/// The family check as `info` reports it: the check (`None` with no sensor), or why it could not
/// measure.
struct FamilyOutcome {
    check: Option<FamilyCheck>,
    unmeasured: Option<String>,
}

impl FamilyOutcome {
    /// The `family:` line, when there is one.
    fn line(&self) -> Option<String> {
        let why = self.unmeasured.as_ref().map(|why| format!("not checked: {why}"));
        self.check.as_ref().map(FamilyCheck::summary).or(why)
    }
}

/// The family check for `info`: the check, or why it could not measure when it left the offset
/// registers as it found them (the rest of `info` stands then); any other failure ends `info`.
fn family_check_for_info<P: Port>(client: &mut Client<P>, info: &DeviceInfo) -> Result<FamilyOutcome, Error> {
    match family_check(client, info) {
        Ok(check) => Ok(FamilyOutcome { check, unmeasured: None }),
        Err(Error::FamilyCheck(error)) if error.left_registers_as_found() => {
            Ok(FamilyOutcome { check: None, unmeasured: Some(error.to_string()) })
        }
        Err(error) => Err(error),
    }
}

/// The first line of a register dump: what a person reporting an unknown part is asked for.
fn dump_heading(info: &DeviceInfo) -> String {
    let sensor = info.sensor.map_or_else(|e| explain(&e), |s| describe_part(&s));
    format!("accelcal {} register dump, firmware {}: {sensor}", env!("CARGO_PKG_VERSION"), firmware_version(info))
}

fn info_json(
    info: &DeviceInfo,
    active: Option<&Calibration>,
    stored: Option<&Calibration>,
    family: FamilyOutcome,
) -> InfoJson {
    InfoJson {
        serial: BoardRecord::of(info).serial,
        protocol_version: info.protocol_version,
        firmware: firmware_version(info),
        part: info.sensor.as_ref().ok().map(part_name),
        who_am_i: info.sensor.as_ref().ok().map(|s| s.who_am_i),
        sensor: info.sensor.map_or_else(|e| SensorJson::Missing { error: explain(&e) }, SensorJson::Found),
        family_confirmed_by: family.check.as_ref().and_then(FamilyCheck::confirmed_by),
        family_check: family.check.as_ref().map(FamilyCheckJson::of),
        family_check_error: family.unmeasured,
        range_g: info.config.range.full_scale_g(),
        sample_rate_hz: info.config.sample_rate_hz,
        active: active.map(CalibrationJson::from_device),
        stored: stored.map(CalibrationJson::from_device),
        registers: None,
    }
}

fn print_info(info: &DeviceInfo, active: Option<&Calibration>, stored: Option<&Calibration>, family: &FamilyOutcome) {
    let serial = BoardRecord::of(info).serial;
    println!("board serial {serial}, firmware {}, protocol {}", firmware_version(info), info.protocol_version);
    match info.sensor {
        Ok(s) => println!("sensor: {}", describe_part(&s)),
        Err(e) => println!("sensor: {}", explain(&e)),
    }
    if let Some(line) = family.line() {
        println!("family: {line}");
    }
    println!("range +-{} g, {} Hz", info.config.range.full_scale_g(), info.config.sample_rate_hz);
    println!("active calibration: {}", active.map_or("none".to_owned(), describe));
    println!("stored calibration: {}", stored.map_or("none".to_owned(), describe));
}

fn firmware_version(info: &DeviceInfo) -> String {
    let f = info.firmware;
    format!("{}.{}.{}", f.major, f.minor, f.patch)
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

/// One row, flushed at once: the stream is live, and a reader that went away shows at the next row.
fn write_row<T: AsRef<[u8]>>(
    out: &mut csv::Writer<impl Write>,
    cells: impl IntoIterator<Item = T>,
) -> std::io::Result<()> {
    out.write_record(cells)?;
    out.flush()
}

/// One sample's cells; every row names the board, so that a file cut or joined still says whose it is.
fn sample_cells(s: &Sample, serial: &str) -> [String; 10] {
    let [ax, ay, az] = s.accel_g.map(|v| format!("{v:.6}"));
    let [gx, gy, gz] = s.gyro_dps.map(|v| format!("{v:.4}"));
    let time_s = format!("{:.6}", s.time_us as f64 * 1e-6);
    [s.index.to_string(), time_s, ax, ay, az, gx, gy, gz, format!("{:.2}", s.temp_c), serial.to_owned()]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Records what reached it in each `write` call, as a pipe's reader would see it arrive.
    #[derive(Default)]
    struct Arrivals(Vec<String>);

    impl Write for Arrivals {
        fn write(&mut self, bytes: &[u8]) -> std::io::Result<usize> {
            self.0.push(String::from_utf8_lossy(bytes).into_owned());
            Ok(bytes.len())
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }

    #[test]
    fn each_sample_reaches_the_reader_as_its_own_line_with_the_stream_s_decimals() {
        let sample = |index: u32| Sample {
            index,
            time_us: 1_250_000 + u64::from(index) * 10_000,
            accel_g: [0.012_345_67, -0.5, 1.000_000_4],
            gyro_dps: [0.123_456, -2.0, 250.0],
            temp_c: 24.126,
        };
        let mut out = csv::Writer::from_writer(Arrivals::default());
        write_row(&mut out, stream_csv_columns()).unwrap();
        write_row(&mut out, sample_cells(&sample(3), "53494D")).unwrap();
        write_row(&mut out, sample_cells(&sample(4), "53494D")).unwrap();
        let arrived = out.into_inner().map_err(|_| "unflushed").unwrap().0;
        // Written literally: the line `accelcal stream` printed before the csv crate wrote it.
        let expected = [
            "index,time_s,ax_g,ay_g,az_g,gx_dps,gy_dps,gz_dps,temp_c,board\n",
            "3,1.280000,0.012346,-0.500000,1.000000,0.1235,-2.0000,250.0000,24.13,53494D\n",
            "4,1.290000,0.012346,-0.500000,1.000000,0.1235,-2.0000,250.0000,24.13,53494D\n",
        ];
        assert_eq!(arrived, expected);
    }
}
