//! `accelcal thermal --sim`: the whole simulated story, the board turned and soaked by the tool. A
//! static calibration at 25 degC, learning while the board warms from 13 to 47 degC and then cools
//! again (heating against cooling compared), and verification at fresh orientations at 15, 25, 35
//! and 45 degC against the truth.

use std::sync::mpsc::Sender;

use rand_xoshiro::rand_core::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;
use shared::linalg::{self, Vec3};
use shared::Calibration;

use super::{random, SimBoard, SimCommand};
use crate::calibration::{self as record, CalibrationJson};
use crate::link::Connection;
use crate::procedure::thermal::error::ThermalError;
use crate::procedure::thermal::learned::{fit_and_activate, hysteresis_of, learn_bins, learn_options, CAPTURE_S};
use crate::procedure::thermal::{capture_now, ThermalBins, ThermalBoard};
use crate::procedure::{corners, faces, ProcedureError};
use crate::report::thermal::{ThermalReport, ThermalRow};
use crate::session::BoardRecord;

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
/// Rest between rounds of captures while learning, in seconds.
const REST_S: f64 = 20.0;

/// How the simulated story goes.
#[derive(Debug, Clone)]
pub struct StoryOptions {
    /// Stop each learning run once the temperature has spanned this much, in degC.
    pub target_span_c: f64,
    /// Fresh orientations verified at each temperature (corners of a turned cube, 1-8).
    pub verify_positions: usize,
    /// Seed of the fresh orientations.
    pub seed: u64,
    /// No live line (the report is printed as JSON).
    pub quiet: bool,
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

/// The simulated story on `board` (behind `connection`): the static calibration, the temperature
/// model learned warming and cooling and made active, and its verification against the truth.
pub fn story(
    connection: &mut Connection,
    board: &SimBoard,
    options: &StoryOptions,
) -> Result<ThermalReport, ThermalError> {
    let mut sim = SimThermal { board, controls: board.controls() };
    sim.settle_at(STATIC_TEMP_C)?;
    let static_calibration = six_faces_on_chip(connection, &mut sim)?;
    sim.settle_at(LEARN_FROM_C)?;
    sim.send(SimCommand::Ambient { target_c: LEARN_AMBIENT_TO_C, c_per_s: LEARN_RAMP_C_PER_S })?;
    let face_forces: Vec<Vec3<f64>> = faces().iter().map(|f| f.up).collect();
    let learn = learn_options(face_forces, options.target_span_c, REST_S);
    let quiet = options.quiet;
    let heating = learn_bins(connection, &mut sim, &learn, quiet, ThermalBins::default(), &mut |_| Ok(()))?;
    // Then the way back down, learned apart, for the heating-versus-cooling comparison.
    let cooling = match heating.complete {
        true => {
            sim.send(SimCommand::Ambient { target_c: LEARN_AMBIENT_BACK_TO_C, c_per_s: LEARN_RAMP_C_PER_S })?;
            Some(learn_bins(connection, &mut sim, &learn, quiet, ThermalBins::default(), &mut |_| Ok(()))?)
        }
        false => None,
    };
    let (calibration, mut fit_json) = fit_and_activate(connection, &static_calibration, &heating, cooling.as_ref())?;
    fit_json.hysteresis = cooling.as_ref().and_then(|c| hysteresis_of(&calibration, &heating.bins, &c.bins));
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(options.seed);
    let mut verification = Vec::new();
    for temp_c in VERIFY_TEMPS_C {
        sim.settle_at(temp_c)?;
        verification.push(verify_row(connection, &mut sim, &calibration, options.verify_positions, &mut rng)?);
    }
    let serial = Some(BoardRecord::of(&connection.info).serial);
    Ok(ThermalReport { serial, calibration: CalibrationJson::from_device(&calibration), fit: fit_json, verification })
}

/// The six faces captured and fitted on the chip: the static calibration.
fn six_faces_on_chip(connection: &mut Connection, sim: &mut SimThermal) -> Result<Calibration, ThermalError> {
    connection.client.clear_positions()?;
    for face in faces() {
        sim.place(face.up)?;
        capture_now(connection, CAPTURE_S)?;
    }
    Ok(connection.client.fit_six_position()?)
}

/// Fresh orientations at one temperature: the |a| error with and without the temperature model.
fn verify_row(
    connection: &mut Connection,
    sim: &mut SimThermal,
    calibration: &Calibration,
    positions: usize,
    rng: &mut Xoshiro256PlusPlus,
) -> Result<ThermalRow, ThermalError> {
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
