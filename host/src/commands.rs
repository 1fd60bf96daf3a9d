//! What each device command of `accelcal` does; `main.rs` parses the arguments and calls these.

use std::io::{BufRead, Write};
use std::path::PathBuf;
use std::time::Duration;

use serde_json::json;
use shared::calibration::{GyroCalibration, ModelTag, Origin, Procedure};
use shared::protocol::{CalibrationSlot, Request, Response, StreamKind, USB_PID, USB_VID};
use shared::{AccelRange, Calibration};

use crate::calibrate::{self, CalibrateOptions, Feedback, Hand, PersonHand};
use crate::connect::{connect, Connection, Target};
use crate::error::{explain, Error};
use crate::session::{CaptureRecord, Session};
use crate::sim::{SimCommand, SimHand};
use crate::ui::{Silent, Terminal};

/// How long the tool waits for the simulated board (which it turns itself) to settle.
const SIM_WAIT_LIMIT: Duration = Duration::from_secs(60);

/// Options of `accelcal calibrate`.
#[derive(Debug, Clone)]
pub struct CalibrateArgs {
    /// The six faces only, fitted on the chip.
    pub quick: bool,
    /// Capture length in seconds.
    pub seconds: u8,
    /// Fresh orientations to verify at.
    pub verify_positions: usize,
    /// Upload and save without asking.
    pub yes: bool,
    /// One JSON object on stdout instead of text.
    pub json: bool,
    /// Where to keep the session (`.json` and `.csv` are added).
    pub session: Option<PathBuf>,
    /// With `--sim`: how far off, in degrees, the tool's hand places the board.
    pub placement_deg: f64,
    /// With `--sim`: seed of the hand's placement errors.
    pub seed: u64,
}

fn feedback(json: bool, yes: bool) -> Box<dyn Feedback> {
    if json {
        Box::new(Silent { yes })
    } else {
        Box::new(Terminal::new(yes))
    }
}

fn hand(connection: &Connection, placement_deg: f64, seed: u64) -> (Box<dyn Hand>, Option<Duration>) {
    match &connection.sim {
        Some(board) => (Box::new(SimHand::new(board.controls(), placement_deg, seed)), Some(SIM_WAIT_LIMIT)),
        None => (Box::new(PersonHand), None),
    }
}

/// The guided calibration, from captures to verification.
pub fn calibrate(target: &Target, args: &CalibrateArgs) -> Result<(), Error> {
    let mut connection = connect(target)?;
    connection.info.sensor.map_err(Error::from)?;
    let range = connection.info.config.range;
    let yes = args.yes || (args.json && connection.sim.is_some());
    let mut feedback = feedback(args.json, yes);
    let (mut hand, wait_limit) = hand(&connection, args.placement_deg, args.seed);
    let options = CalibrateOptions {
        quick: args.quick,
        seconds: args.seconds,
        verify_positions: args.verify_positions,
        wait_limit,
    };
    let targets = if args.quick { calibrate::faces() } else { [calibrate::faces(), calibrate::corners()].concat() };
    let client = &mut connection.client;
    let session = calibrate::collect(client, hand.as_mut(), &targets, &options, feedback.as_mut())?;
    if let Some(path) = &args.session {
        session.save(path)?;
    }
    let chip = calibrate::chip_fit(client)?;
    let (chosen, host) = if args.quick {
        (chip, None)
    } else {
        let fit = calibrate::host_fit(&session)?;
        (calibrate::calibration_from_fit(&fit, &session, range)?, Some(fit))
    };
    feedback.say(&describe(&chosen));
    if let Some(fit) = &host {
        for p in &fit.parameters {
            let error = p.std_error.map_or(String::new(), |e| format!(" +- {e:.1e}"));
            feedback.say(&format!("  {:<5} {:+.6}{error}", p.name, p.value));
        }
        feedback.say(&format!("on-chip six-position fit for comparison: {}", describe(&chip)));
    }
    if !feedback.confirm("Upload this calibration to the board and save it in flash?") {
        feedback.say("not uploaded; the board keeps its previous calibration");
        return Ok(());
    }
    calibrate::upload_and_save(client, &chosen)?;
    feedback.say("uploaded and saved; now checking it at fresh orientations");
    let verification =
        calibrate::verify(client, hand.as_mut(), options.verify_positions, wait_limit, feedback.as_mut())?;
    if args.json {
        let truth = connection.sim.as_ref().map(|board| {
            let truth = board.truth();
            json!({ "matrix": truth.matrix, "offset": truth.offset_g, "gyro_bias_dps": truth.gyro_bias_dps })
        });
        let output = json!({
            "calibration": calibration_json(&chosen),
            "truth": truth,
            "verification": verification,
            "captures": session.captures.len(),
            "chip_six_position": calibration_json(&chip),
            "host_fit": host.as_ref().map(|f| json!({
                "model": f.model.name(),
                "cost": f.cost,
                "iterations": f.iterations,
                "std_errors": f.parameters.iter().map(|p| (p.name.clone(), p.std_error)).collect::<std::collections::BTreeMap<_, _>>(),
            })),
        });
        println!("{output:#}");
    } else {
        println!(
            "verified at {} fresh orientations: | |a| - 1 g | rms {:.2} mg before, {:.3} mg after (worst {:.3} mg)",
            verification.positions, verification.before_rms_mg, verification.after_rms_mg, verification.after_max_mg
        );
    }
    Ok(())
}

fn describe(calibration: &Calibration) -> String {
    let m = calibration.matrix;
    let o = calibration.offset_g.map(|v| v * 1000.0);
    format!(
        "{}: scale {:.5} {:.5} {:.5}, offset {:+.2} {:+.2} {:+.2} mg, residual {:.3} mg",
        calibration.origin.model.as_str(),
        m[0][0],
        m[1][1],
        m[2][2],
        o[0],
        o[1],
        o[2],
        calibration.residual_mg
    )
}

/// A calibration as JSON, under the convention a = matrix (m - offset), in g.
pub fn calibration_json(calibration: &Calibration) -> serde_json::Value {
    json!({
        "model": calibration.origin.model.as_str(),
        "matrix": calibration.matrix,
        "offset": calibration.offset_g,
        "gyro_bias_dps": calibration.gyro.bias_dps,
        "range_g": calibration.range.full_scale_g(),
        "temp_c": calibration.mean_temp_c,
        "residual_mg": calibration.residual_mg,
    })
}

/// Reads a calibration written by `download` or by `fit --json` on data in g.
pub fn calibration_from_json(text: &str, range: AccelRange) -> Result<Calibration, Error> {
    let value: serde_json::Value =
        serde_json::from_str(text).map_err(|e| Error::Refused(format!("not a JSON calibration: {e}")))?;
    if value.get("g").and_then(|g| g.as_f64()).is_some_and(|g| (g - 1.0).abs() > 1e-12) {
        return Err(Error::Refused("this fit is not in g: fit data in g with --g 1 before uploading".into()));
    }
    let array = |key: &str| -> Option<Vec<f32>> {
        let items = value.get(key)?.as_array()?;
        items
            .iter()
            .flat_map(|v| v.as_array().cloned().unwrap_or_else(|| vec![v.clone()]))
            .map(|v| v.as_f64().map(|f| f as f32))
            .collect()
    };
    let matrix =
        array("matrix").filter(|m| m.len() == 9).ok_or_else(|| Error::Refused("no 3 x 3 \"matrix\"".into()))?;
    let offset =
        array("offset").filter(|o| o.len() == 3).ok_or_else(|| Error::Refused("no 3-element \"offset\"".into()))?;
    let gyro = array("gyro_bias_dps").filter(|g| g.len() == 3).unwrap_or(vec![0.0; 3]);
    let model_name = value.get("model").and_then(|m| m.as_str()).unwrap_or("");
    let origin = Origin { procedure: Procedure::Uploaded, model: ModelTag::new(model_name).unwrap_or_default() };
    let range = value
        .get("range_g")
        .and_then(|r| r.as_u64())
        .and_then(|r| AccelRange::from_full_scale_g(r as u8))
        .unwrap_or(range);
    let calibration = Calibration {
        matrix: [
            [matrix[0], matrix[1], matrix[2]],
            [matrix[3], matrix[4], matrix[5]],
            [matrix[6], matrix[7], matrix[8]],
        ],
        offset_g: [offset[0], offset[1], offset[2]],
        gyro: GyroCalibration { bias_dps: [gyro[0], gyro[1], gyro[2]], ..GyroCalibration::default() },
        origin,
        range,
        mean_temp_c: value.get("temp_c").and_then(|t| t.as_f64()).unwrap_or(0.0) as f32,
        temperature: None,
        residual_mg: value.get("residual_mg").and_then(|t| t.as_f64()).unwrap_or(0.0) as f32,
    };
    calibration.validate().map_err(|reason| {
        Error::Refused(format!("refused before upload: {}", crate::error::calibration_reason(&reason)))
    })?;
    Ok(calibration)
}

/// `accelcal info`.
pub fn info(target: &Target, json_output: bool) -> Result<(), Error> {
    let mut connection = connect(target)?;
    let info = connection.info.clone();
    let active = read_calibration(&mut connection, CalibrationSlot::Active)?;
    let stored = read_calibration(&mut connection, CalibrationSlot::Stored)?;
    if json_output {
        let sensor = match info.sensor {
            Ok(s) => json!({ "address": s.address, "who_am_i": s.who_am_i, "genuine": s.genuine }),
            Err(e) => json!({ "error": explain(&e) }),
        };
        let output = json!({
            "protocol_version": info.protocol_version,
            "firmware": format!("{}.{}.{}", info.firmware.major, info.firmware.minor, info.firmware.patch),
            "sensor": sensor,
            "range_g": info.config.range.full_scale_g(),
            "sample_rate_hz": info.config.sample_rate_hz,
            "active": active.as_ref().map(calibration_json),
            "stored": stored.as_ref().map(calibration_json),
        });
        println!("{output:#}");
        return Ok(());
    }
    let f = info.firmware;
    println!("firmware {}.{}.{}, protocol {}", f.major, f.minor, f.patch, info.protocol_version);
    match info.sensor {
        Ok(s) if s.genuine => println!("sensor: MPU-6050 at 0x{:02x}", s.address),
        Ok(s) => println!("sensor: MPU-6050-compatible clone (WHO_AM_I 0x{:02x}) at 0x{:02x}", s.who_am_i, s.address),
        Err(e) => println!("sensor: {}", explain(&e)),
    }
    println!("range +-{} g, {} Hz", info.config.range.full_scale_g(), info.config.sample_rate_hz);
    println!("active calibration: {}", active.as_ref().map_or("none".to_owned(), describe));
    println!("stored calibration: {}", stored.as_ref().map_or("none".to_owned(), describe));
    Ok(())
}

fn read_calibration(connection: &mut Connection, slot: CalibrationSlot) -> Result<Option<Calibration>, Error> {
    match connection.client.call(Request::GetCalibration(slot))? {
        Response::Calibration(calibration) => Ok(calibration),
        other => Err(Error::Protocol(format!("{other:?}"))),
    }
}

/// `accelcal download`: the active (or stored) calibration as JSON.
pub fn download(target: &Target, stored: bool) -> Result<(), Error> {
    let mut connection = connect(target)?;
    let slot = if stored { CalibrationSlot::Stored } else { CalibrationSlot::Active };
    match read_calibration(&mut connection, slot)? {
        Some(calibration) => println!("{:#}", calibration_json(&calibration)),
        None => return Err(Error::Refused("the device has no calibration to download".into())),
    }
    Ok(())
}

/// `accelcal upload FILE [--save]`.
pub fn upload(target: &Target, file: &std::path::Path, save: bool) -> Result<(), Error> {
    let text = std::fs::read_to_string(file).map_err(|e| Error::io(format!("reading {}", file.display()), e))?;
    let mut connection = connect(target)?;
    let calibration = calibration_from_json(&text, connection.info.config.range)?;
    connection.client.call(Request::SetCalibration(calibration))?;
    if save {
        connection.client.call(Request::SaveCalibration)?;
    }
    println!(
        "uploaded {}{}",
        describe(&calibration),
        if save { " and saved" } else { " (active until reset; run save to keep it)" }
    );
    Ok(())
}

/// `accelcal save` / `accelcal erase`.
pub fn simple(target: &Target, request: Request, done: &str) -> Result<(), Error> {
    let mut connection = connect(target)?;
    connection.client.call(request)?;
    println!("{done}");
    Ok(())
}

/// `accelcal stream`: samples as CSV on stdout.
pub fn stream(target: &Target, calibrated: bool, count: u32, rate_hz: u16) -> Result<(), Error> {
    let mut connection = connect(target)?;
    let kind = if calibrated { StreamKind::Calibrated } else { StreamKind::Raw };
    let stdout = std::io::stdout();
    let mut out = stdout.lock();
    let _ = writeln!(out, "index,ax_g,ay_g,az_g,gx_dps,gy_dps,gz_dps,temp_c");
    connection.client.run(Request::Stream { kind, rate_hz, count }, |update| {
        if let Response::Sample(s) = update {
            let [ax, ay, az] = s.accel_g;
            let [gx, gy, gz] = s.gyro_dps;
            let _ = writeln!(out, "{},{ax:.6},{ay:.6},{az:.6},{gx:.4},{gy:.4},{gz:.4},{:.2}", s.index, s.temp_c);
        }
    })?;
    Ok(())
}

/// `accelcal capture`: one position, appended to a session file.
pub fn capture(target: &Target, session_stem: &std::path::Path, name: &str, seconds: u8) -> Result<(), Error> {
    let json_path = session_stem.with_extension("json");
    let mut session = if json_path.exists() { Session::load(&json_path)? } else { Session::default() };
    let mut connection = connect(target)?;
    connection.info.sensor.map_err(Error::from)?;
    let mut feedback = Terminal::new(true);
    let response = connection.client.run(Request::Capture { seconds }, |update| {
        if let Response::Progress(p) = update {
            feedback.progress(p.samples, p.total_samples);
        }
    });
    feedback.progress_done();
    let Response::Captured { stats, position } = response? else {
        return Err(Error::Protocol("a capture ended without its result".into()));
    };
    session.captures.push(CaptureRecord {
        target: name.to_owned(),
        position: position.map(|p| p.name().to_owned()),
        unix_time_s: crate::session::unix_time_s(),
        stats,
    });
    session.save(session_stem)?;
    let [x, y, z] = stats.mean_g;
    println!(
        "captured {name}: mean {x:+.5} {y:+.5} {z:+.5} g over {} samples; {} captures in the session",
        stats.samples,
        session.captures.len()
    );
    Ok(())
}

/// `accelcal verify`.
pub fn verify(target: &Target, positions: usize, placement_deg: f64, seed: u64) -> Result<(), Error> {
    let mut connection = connect(target)?;
    let mut feedback = Terminal::new(true);
    let (mut hand, wait_limit) = hand(&connection, placement_deg, seed);
    let v = calibrate::verify(&mut connection.client, hand.as_mut(), positions, wait_limit, &mut feedback)?;
    println!(
        "| |a| - 1 g | rms {:.2} mg raw, {:.3} mg calibrated (worst {:.3} mg); chip and host agree within {:.2} mg",
        v.before_rms_mg, v.after_rms_mg, v.after_max_mg, v.on_chip_difference_mg
    );
    Ok(())
}

/// `accelcal ports`: serial ports, ours marked.
pub fn ports() -> Result<(), Error> {
    let ports = serialport::available_ports().map_err(|e| Error::Refused(format!("cannot list serial ports: {e}")))?;
    if ports.is_empty() {
        println!("no serial ports found; is the board plugged in?");
    }
    for port in ports {
        let ours = matches!(&port.port_type, serialport::SerialPortType::UsbPort(usb) if usb.vid == USB_VID && usb.pid == USB_PID);
        println!("{}{}", port.port_name, if ours { "  <- accelcal board" } else { "" });
    }
    Ok(())
}

/// `accelcal sim --pty`: serves a simulated board on a pseudo-terminal until killed; prints the
/// path first. Lines on stdin turn the board: `place X Y Z`, `place +X`, `disconnect`, `connect`.
pub fn sim_pty(seed: u64) -> Result<(), Error> {
    let (master, slave) =
        serialport::TTYPort::pair().map_err(|e| Error::Refused(format!("cannot create a pseudo-terminal: {e}")))?;
    let path =
        serialport::SerialPort::name(&slave).ok_or_else(|| Error::Refused("the pseudo-terminal has no name".into()))?;
    let board = crate::sim::SimBoard::spawn(master, firmware::sim::SimFlash::new(), seed);
    println!("{path}");
    let _ = std::io::stdout().flush();
    let controls = board.controls();
    for line in std::io::stdin().lock().lines().map_while(Result::ok) {
        match parse_sim_command(&line) {
            Some(command) => {
                let _ = controls.send(command);
            }
            None => eprintln!("unknown command {line:?}: use place X Y Z, place +X, disconnect, connect"),
        }
    }
    // NOTE: keep the slave end open: with no open slave, reads on the master fail.
    let _keep_open = slave;
    loop {
        std::thread::park();
    }
}

fn parse_sim_command(line: &str) -> Option<SimCommand> {
    let words: Vec<&str> = line.split_whitespace().collect();
    match words.as_slice() {
        ["place", face] => shared::Position::ALL
            .iter()
            .find(|p| p.name().eq_ignore_ascii_case(face))
            .map(|p| SimCommand::Place(p.specific_force_g())),
        ["place", x, y, z] => Some(SimCommand::Place([x.parse().ok()?, y.parse().ok()?, z.parse().ok()?])),
        ["disconnect"] => Some(SimCommand::Connect(false)),
        ["connect"] => Some(SimCommand::Connect(true)),
        _ => None,
    }
}
