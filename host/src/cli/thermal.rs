//! `accelcal thermal`: learns how the sensor drifts with temperature, fits the temperature model
//! around the static calibration and makes it active on the chip. With `--sim` it runs the whole
//! simulated story: a static calibration at 25 degC, learning while the board warms from 13 to 47
//! degC, and verification at fresh orientations at 15, 25, 35 and 45 degC against the truth.
//!
//! `accelcal thermal --port`: a person's board rests in one orientation while its temperature
//! changes. The learned bins are kept on disk after every capture and a later run goes on from them
//! (`--bins`); Ctrl-C ends the learning and fits what it learned.

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::Sender;
use std::sync::Arc;
use std::time::{Duration, Instant};

use rand_xoshiro::rand_core::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;
use shared::linalg::{self, Vec3};
use shared::protocol::CalibrationSlot;
use shared::Calibration;

use super::args::ThermalArgs;
use super::terminal::interrupt_on_ctrl_c;
use crate::calibration::{self as record, CalibrationJson};
use crate::error::Error;
use crate::fit::hysteresis::{self, Hysteresis};
use crate::fit::thermal::fit_temperature;
use crate::link::{Connection, LinkError};
use crate::procedure::thermal::{capture_now, learn, LearnEnd, LearnOptions, LearnStatus, ThermalBins, ThermalBoard};
use crate::procedure::{corners, faces, ProcedureError};
use crate::report::thermal::{ThermalFitJson, ThermalReport, ThermalRow};
use crate::session::{unix_time_s, BoardRecord};
use crate::sim::{random, SimBoard, SimCommand};

/// The reported temperatures the simulated story verifies at, in degC.
const VERIFY_TEMPS_C: [f32; 4] = [15.0, 25.0, 35.0, 45.0];
/// The reported temperature of the simulated static calibration, in degC.
const STATIC_TEMP_C: f32 = 25.0;
/// The simulated learning run: from this reported temperature ...
const LEARN_FROM_C: f32 = 13.0;
/// ... while the surroundings warm to this, in degC ...
const LEARN_AMBIENT_TO_C: f32 = 44.0;
/// ... at 1 degC a minute, in degC/s; and then back down to this, in degC.
const LEARN_RAMP_C_PER_S: f32 = 1.0 / 60.0;
/// Where the surroundings cool to after the warming run (the die follows them down past 13 degC).
const LEARN_AMBIENT_BACK_TO_C: f32 = 2.0;
/// Long enough for the die to settle: ten time constants of the simulated board, in seconds.
const SOAK_S: f32 = 2400.0;
/// Capture length while learning and verifying, in seconds.
const CAPTURE_S: u8 = 5;

/// Runs `accelcal thermal`.
pub(super) fn thermal(args: &ThermalArgs) -> Result<(), Error> {
    let mut opened = args.device.open()?;
    opened.connection.info.sensor.map_err(LinkError::from)?;
    let report = match opened.sim.take() {
        Some(board) => sim_story(&mut opened.connection, &board, args)?,
        None => person_run(&mut opened.connection, args)?,
    };
    if args.json {
        println!("{}", report.json());
    } else {
        print!("{}", report.text());
    }
    Ok(())
}

/// The simulated board, turned and soaked by the tool.
struct SimThermal<'a> {
    board: &'a SimBoard,
    controls: Sender<SimCommand>,
}

impl SimThermal<'_> {
    fn send(&self, command: SimCommand) -> Result<(), ProcedureError> {
        self.controls.send(command).map_err(|_| ProcedureError::SimulatedBoardStopped)
    }

    /// Soaks the board until its sensor reports `reading_c`.
    fn settle_at(&mut self, reading_c: f32) -> Result<(), ProcedureError> {
        let target_c = self.board.ambient_for(reading_c);
        self.send(SimCommand::Ambient { target_c, c_per_s: f32::INFINITY })?;
        self.send(SimCommand::Elapse(SOAK_S))
    }
}

impl ThermalBoard for SimThermal<'_> {
    fn place(&mut self, force_g: Vec3<f64>) -> Result<(), ProcedureError> {
        self.send(SimCommand::Place(force_g.map(|v| v as f32)))
    }

    fn rest(&mut self, seconds: f64) -> Result<(), ProcedureError> {
        self.send(SimCommand::Elapse(seconds as f32))
    }
}

fn sim_story(connection: &mut Connection, board: &SimBoard, args: &ThermalArgs) -> Result<ThermalReport, Error> {
    let mut sim = SimThermal { board, controls: board.controls() };
    sim.settle_at(STATIC_TEMP_C)?;
    let static_calibration = six_faces_on_chip(connection, &mut sim)?;
    sim.settle_at(LEARN_FROM_C)?;
    sim.send(SimCommand::Ambient { target_c: LEARN_AMBIENT_TO_C, c_per_s: LEARN_RAMP_C_PER_S })?;
    let face_forces: Vec<Vec3<f64>> = faces().iter().map(|f| f.up).collect();
    let options = learn_options(face_forces, args.target_span_c, 20.0);
    let heating = learn_bins(connection, &mut sim, &options, args.json, ThermalBins::default(), &mut |_| Ok(()))?;
    // Then the way back down, learned apart, for the heating-versus-cooling comparison.
    let cooling = match heating.complete {
        true => {
            sim.send(SimCommand::Ambient { target_c: LEARN_AMBIENT_BACK_TO_C, c_per_s: LEARN_RAMP_C_PER_S })?;
            Some(learn_bins(connection, &mut sim, &options, args.json, ThermalBins::default(), &mut |_| Ok(()))?)
        }
        false => None,
    };
    let (calibration, mut fit_json) = fit_and_activate(connection, &static_calibration, &heating, cooling.as_ref())?;
    fit_json.hysteresis = cooling.as_ref().and_then(|c| hysteresis_of(&calibration, &heating.bins, &c.bins));
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(args.device.seed);
    let mut verification = Vec::new();
    for temp_c in VERIFY_TEMPS_C {
        sim.settle_at(temp_c)?;
        verification.push(verify_row(connection, &mut sim, &calibration, usize::from(args.verify), &mut rng)?);
    }
    let serial = Some(BoardRecord::of(&connection.info).serial);
    Ok(ThermalReport { serial, calibration: CalibrationJson::from_device(&calibration), fit: fit_json, verification })
}

/// The six faces captured and fitted on the chip: the static calibration.
fn six_faces_on_chip(connection: &mut Connection, sim: &mut SimThermal) -> Result<Calibration, Error> {
    connection.client.clear_positions()?;
    for face in faces() {
        sim.place(face.up)?;
        capture_now(connection, CAPTURE_S)?;
    }
    Ok(connection.client.fit_six_position()?)
}

fn learn_options(faces: Vec<Vec3<f64>>, target_span_c: f64, rest_seconds: f64) -> LearnOptions {
    LearnOptions { faces, capture_seconds: CAPTURE_S, rest_seconds, target_span_c, max_rounds: 10_000 }
}

/// What one learning run gathered.
struct Learned {
    bins: ThermalBins,
    /// Why it stopped.
    stopped: String,
    /// Whether it ran to its end (not interrupted).
    complete: bool,
}

/// Learns into `bins` with the live line on a terminal, giving the bins to `keep` after every
/// capture; an interrupted run keeps its bins when they span enough.
fn learn_bins(
    connection: &mut Connection,
    board: &mut dyn ThermalBoard,
    options: &LearnOptions,
    quiet: bool,
    mut bins: ThermalBins,
    keep: &mut dyn FnMut(&ThermalBins) -> Result<(), ProcedureError>,
) -> Result<Learned, Error> {
    // NOTE: a live line rewrites itself on a terminal; in a log it would be one endless line.
    let quiet = quiet || !std::io::stderr().is_terminal();
    let mut show = |s: LearnStatus, learned: &ThermalBins| {
        if !quiet {
            let (temp, span, bins, chip) = (s.temp_c, s.span_c, s.bins, s.chip_bins);
            eprint!("\rtemperature {temp:5.1} degC, span {span:4.1} degC, {bins:3} bins (chip bins in the last capture: {chip})");
        }
        keep(learned)
    };
    let learned = learn(connection, board, options, &mut bins, &mut show);
    if !quiet {
        eprintln!();
    }
    match learned {
        Ok(end) => Ok(Learned { bins, stopped: end_text(end).to_owned(), complete: true }),
        Err(error) if bins.check_span().is_ok() => {
            Ok(Learned { bins, stopped: format!("interrupted ({error}); fitted what was learned"), complete: false })
        }
        Err(error) => Err(error.into()),
    }
}

/// Fits the bins of one or two runs and makes the combined calibration active.
fn fit_and_activate(
    connection: &mut Connection,
    static_calibration: &Calibration,
    first: &Learned,
    second: Option<&Learned>,
) -> Result<(Calibration, ThermalFitJson), Error> {
    first.bins.check_span()?;
    let mut points = first.bins.points();
    points.extend(second.map(|s| s.bins.points()).unwrap_or_default());
    let fit = fit_temperature(&record::thermal_reference(static_calibration), &points)?;
    let calibration = record::with_temperature(static_calibration, fit.model)?;
    connection.client.set_calibration(calibration)?;
    let temps = points.iter().map(|p| p.temp_c);
    let learned = [temps.clone().fold(f64::MAX, f64::min), temps.fold(f64::MIN, f64::max)];
    let bins = first.bins.len() + second.map_or(0, |s| s.bins.len());
    let stopped =
        second.map_or(first.stopped.clone(), |s| format!("warming: {}; cooling: {}", first.stopped, s.stopped));
    Ok((calibration, ThermalFitJson::new(&fit, &points, bins, learned, stopped)))
}

/// The heating-versus-cooling comparison around the calibration's static matrix and temperature model.
fn hysteresis_of(calibration: &Calibration, heating: &ThermalBins, cooling: &ThermalBins) -> Option<Hysteresis> {
    let model = calibration.temperature?;
    let (matrix, _) = record::static_part(calibration);
    hysteresis::compare(&model, &matrix, &heating.points(), &cooling.points())
}

fn end_text(end: LearnEnd) -> &'static str {
    match end {
        LearnEnd::SpanReached => "the span was reached",
        LearnEnd::Stalled => "the temperature stalled",
        LearnEnd::RoundLimit => "the round limit was reached",
    }
}

/// Fresh orientations at one temperature: the |a| error with and without the temperature model.
fn verify_row(
    connection: &mut Connection,
    sim: &mut SimThermal,
    calibration: &Calibration,
    positions: usize,
    rng: &mut Xoshiro256PlusPlus,
) -> Result<ThermalRow, Error> {
    let (mut static_sq, mut compensated_sq, mut temp_sum) = (0.0, 0.0, 0.0);
    for up in fresh_orientations(rng).into_iter().take(positions) {
        sim.place(up)?;
        let stats = capture_now(connection, CAPTURE_S)?;
        let norm_error = |a: Vec3<f32>| f64::from(linalg::norm(a)) - 1.0;
        static_sq += norm_error(calibration.apply(stats.mean_g)).powi(2);
        compensated_sq += norm_error(calibration.apply_at(stats.mean_g, stats.temp_c)).powi(2);
        temp_sum += f64::from(stats.temp_c);
    }
    let n = positions.max(1) as f64;
    let temp_c = temp_sum / n;
    let mut row = truth_row(sim.board, calibration, temp_c as f32);
    row.uncompensated_rms_mg = (static_sq / n).sqrt() * 1000.0;
    row.compensated_rms_mg = (compensated_sq / n).sqrt() * 1000.0;
    row.positions = positions;
    Ok(row)
}

/// The eight corners of a cube turned about a random axis by a random angle: fresh orientations,
/// spread evenly, so the rms |a| error they show does not hinge on where a few random draws fell
/// (an offset error e shows as |e| / sqrt(3) rms over them, in any direction).
fn fresh_orientations(rng: &mut Xoshiro256PlusPlus) -> Vec<Vec3<f64>> {
    let axis = random::random_unit(rng);
    let angle = random::gaussian(rng).atan2(random::gaussian(rng));
    let (sin, cos) = angle.sin_cos();
    let turn = |v: Vec3<f64>| {
        let along = linalg::scale(axis, linalg::dot(axis, v) * (1.0 - cos));
        linalg::add(linalg::add(linalg::scale(v, cos), linalg::scale(linalg::cross(axis, v), sin)), along)
    };
    corners().iter().map(|corner| turn(corner.up)).collect()
}

/// The truth, the applied and the static correction at `temp_c`, and the gyro bias error.
fn truth_row(board: &SimBoard, calibration: &Calibration, temp_c: f32) -> ThermalRow {
    let truth = board.truth_at(temp_c);
    let (applied_matrix, applied_offset) = record::applied_at(calibration, temp_c);
    let (static_matrix, static_offset) = record::static_part(calibration);
    let bias = record::gyro_bias_at(calibration, temp_c);
    let gyro_error = (0..3).map(|k| (bias[k] - f64::from(truth.gyro_bias_dps[k])).abs()).fold(0.0, f64::max);
    ThermalRow {
        temp_c: f64::from(temp_c),
        matrix: truth.matrix.map(|row| row.map(f64::from)),
        offset: truth.offset_g.map(f64::from),
        applied_matrix,
        applied_offset,
        static_matrix,
        static_offset,
        uncompensated_rms_mg: 0.0,
        compensated_rms_mg: 0.0,
        gyro_bias_error_dps: gyro_error,
        positions: 0,
    }
}

/// Rest between rounds of captures on a person's board, in seconds.
const REST_S: f64 = 30.0;
/// How often a resting board looks for Ctrl-C, so that it ends at once.
const INTERRUPT_POLL: Duration = Duration::from_millis(100);

/// A person's board: it rests where it is while real time passes, until Ctrl-C.
struct RestingBoard {
    interrupt: Arc<AtomicBool>,
}

impl ThermalBoard for RestingBoard {
    fn place(&mut self, _force_g: Vec3<f64>) -> Result<(), ProcedureError> {
        Ok(())
    }

    fn rest(&mut self, seconds: f64) -> Result<(), ProcedureError> {
        let until = Instant::now() + Duration::from_secs_f64(seconds);
        while Instant::now() < until {
            if self.interrupt.load(Ordering::SeqCst) {
                return Err(LinkError::Interrupted.into());
            }
            std::thread::sleep(INTERRUPT_POLL);
        }
        Ok(())
    }
}

/// Learns around the calibration active on the board, keeping the bins in `--bins` (or a file
/// named by the time), and makes the fitted temperature model active.
fn person_run(connection: &mut Connection, args: &ThermalArgs) -> Result<ThermalReport, Error> {
    let active = connection.client.calibration(CalibrationSlot::Active)?.ok_or(ProcedureError::NoActiveCalibration)?;
    let serial = BoardRecord::of(&connection.info).serial;
    let path =
        args.bins.clone().unwrap_or_else(|| PathBuf::from(format!("accelcal-thermal-{}.json", unix_time_s() as u64)));
    let bins = kept_or_new(&path, &serial)?;
    let interrupt = interrupt_on_ctrl_c();
    connection.client.interrupt_on(interrupt.clone());
    let options = learn_options(vec![[0.0, 0.0, 1.0]], args.target_span_c, REST_S);
    let mut keep = |bins: &ThermalBins| bins.save(&path, &serial).map_err(ProcedureError::from);
    let mut board = RestingBoard { interrupt: interrupt.clone() };
    let learned = learn_bins(connection, &mut board, &options, args.json, bins, &mut keep);
    // NOTE: Ctrl-C ended the learning; the fit is still made active on the board.
    interrupt.store(false, Ordering::SeqCst);
    let fitted = learned.and_then(|learned| fit_and_activate(connection, &active, &learned, None));
    let (calibration, fit) = fitted.map_err(|source| Error::ThermalStopped {
        source: Box::new(source),
        span_c: ThermalBins::load(&path, &serial).map_or(0.0, |bins| bins.span_c()),
        path: path.clone(),
        device: args.device.port.clone().unwrap_or_default(),
    })?;
    eprintln!("the learned bins are kept in {}", path.display());
    let (serial, calibration) = (Some(serial), CalibrationJson::from_device(&calibration));
    Ok(ThermalReport { serial, calibration, fit, verification: Vec::new() })
}

/// The bins an earlier run kept at `path` on this board, or none when there is no such file.
fn kept_or_new(path: &Path, serial: &str) -> Result<ThermalBins, Error> {
    if !path.exists() {
        eprintln!("the learned bins are kept in {} as they are learned", path.display());
        return Ok(ThermalBins::default());
    }
    let bins = ThermalBins::load(path, serial)?;
    let (low, high) = bins.range_c().unwrap_or_default();
    eprintln!("going on from the {} bins ({low:.1} to {high:.1} degC) kept in {}", bins.len(), path.display());
    Ok(bins)
}
