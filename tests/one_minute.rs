//! Calibration in one minute (issue 16): over 20 seeds of the realistic simulated sensor (warming
//! about 5 degC with a 4-minute time constant from power-on) and a hand that places the board 3
//! degrees off and turns at a person's pace, the default adaptive session keeps the board at most
//! 60 s from its first capture to the end of its verification, and its calibration is within 0.2 mg
//! rms of the sensor's truth at fresh orientations at the temperature it was made at (the captures'
//! mean, as the quick mode's figure). Its fitted drift carries it to the end temperature too,
//! measured against the static fit of the same captures there.

use std::sync::{Arc, OnceLock};
use std::time::Duration;

use accelcal::calibration::from_fit;
use accelcal::fit::thermal::fit_temperature;
use accelcal::link::{pipe, Client, PipeEnd, StreamRequest};
use accelcal::procedure::stop_rule::{CaptureLength, Noise, StopRule};
use accelcal::procedure::thermal::{capture_now, learn, LearnOptions, ThermalBins, ThermalBoard};
use accelcal::procedure::{self, AdaptiveOptions, Moves, ProcedureError, Silent, Turning};
use accelcal::session::Session;
use accelcal::sim::SimulatedHand;
use accelcal::sim::{Pace, SimBoard, SimCommand, SimSensor};
use firmware::sim::SimFlash;
use shared::protocol::{CalibrationSlot, SensorConfig, StreamKind};
use shared::Calibration;

const PLACEMENT_DEG: f64 = 3.0;
const TARGET_MG: f64 = 0.2;
const SEEDS: u64 = 20;
const WAIT: Option<Duration> = Some(Duration::from_secs(60));
/// The die temperature TEMP_OUT reads now (one raw sample: 10 ms of the board's time).
fn reading_now(client: &mut Client<PipeEnd>) -> f32 {
    let mut temp_c = f32::NAN;
    let request = StreamRequest { kind: StreamKind::Raw, rate_hz: 100, count: 1 };
    client.stream(request, |sample| temp_c = sample.temp_c).unwrap();
    temp_c
}

/// One default adaptive session's figures.
struct Outcome {
    captures: usize,
    board_seconds: f64,
    /// Seconds of those the positions' captures averaged.
    averaged_s: f64,
    temp_change_c: f64,
    /// The calibration (with its fitted drift) at the temperature the session ends at, mg rms.
    at_end_mg: f64,
    /// The same at the captures' mean temperature (what the drift did to the nine parameters).
    at_mean_mg: f64,
    /// The static nine-parameter fit of the same captures at the end temperature.
    static_at_end_mg: f64,
    /// The static fit at the captures' mean temperature (what ordering alone does).
    static_at_mean_mg: f64,
    verified_mg: f64,
}

/// The default session, as `calibrate --sim` runs it: the stop rule at the default target, the
/// hand turning like a person, three verifications as long as the target needs.
fn session(seed: u64, kind: SimSensor, target_mg: f64) -> Outcome {
    session_on(seed, kind, target_mg, None)
}

/// The default session on a board that was powered on afresh, with `learned` active on it (as
/// `calibrate` finds a calibration that `accelcal thermal` left in the board's flash).
fn session_on(seed: u64, kind: SimSensor, target_mg: f64, learned: Option<Calibration>) -> Outcome {
    let (host, device) = pipe();
    let board = SimBoard::spawn_with(device, SimFlash::new(), seed, kind, Pace::Lockstep);
    let (mut client, _) = Client::connect(host).unwrap();
    let mut hand = SimulatedHand::new(board.controls(), PLACEMENT_DEG, seed);
    let rule = StopRule { target_mg, noise: Noise::Measured, rate_hz: 100 };
    let options = AdaptiveOptions { rule: rule.clone(), wait_limit: WAIT, clock: Some(Arc::new(board.clock())) };
    let (mut session, mut feedback) = (Session::default(), Silent { yes: true });
    if let Some(calibration) = learned {
        client.set_calibration(calibration).unwrap();
        session.learned = accelcal::fit::drift::learned::kept(client.calibration(CalibrationSlot::Active).unwrap());
        assert!(session.learned.is_some(), "the learned model is found on the board");
    }
    let targets = procedure::targets(false);
    let collected = procedure::collect_adaptive(
        &mut client,
        Turning { hand: &mut hand, moves: &mut Moves::at(rule.rate_hz) },
        &targets,
        &options,
        &mut feedback,
        &mut session,
        &mut |_| Ok(()),
    )
    .unwrap();
    let calibration = session.outcome(SensorConfig::default()).unwrap().calibration;
    let static_fit = accelcal::fit::drift::ortho9(&session.dataset()).unwrap();
    let static_calibration = from_fit(&static_fit, &session.dataset(), SensorConfig::default()).unwrap();
    client.set_calibration(calibration).unwrap();
    let calibrated: Vec<[f64; 3]> = session.captures.iter().map(|c| c.stats.mean_g.map(f64::from)).collect();
    let length = CaptureLength::Goal(rule.verification_goal());
    let verification =
        procedure::verify_with(&mut client, &mut hand, 3, WAIT, &mut feedback, &calibrated, length).unwrap();
    let board_seconds = board.clock()() - collected.first_capture_s.unwrap();
    let end_c = reading_now(&mut client);
    let (low, high) = accelcal::fit::drift::span_c(&session.dataset());
    Outcome {
        captures: session.captures.len(),
        board_seconds,
        averaged_s: session.captures.iter().map(|c| f64::from(c.stats.seconds)).sum(),
        temp_change_c: high - low,
        at_end_mg: board.true_error_mg(&calibration, end_c),
        at_mean_mg: board.true_error_mg(&calibration, accelcal::fit::drift::mean_temp_c(&session.dataset()) as f32),
        static_at_end_mg: board.true_error_mg(&static_calibration, end_c),
        static_at_mean_mg: board
            .true_error_mg(&static_calibration, accelcal::fit::drift::mean_temp_c(&session.dataset()) as f32),
        verified_mg: verification.after_rms_mg,
    }
}

/// The simulated board, turned and soaked by the learning run.
struct Soaked(std::sync::mpsc::Sender<SimCommand>);

impl ThermalBoard for Soaked {
    fn place(&mut self, force_g: [f64; 3]) -> Result<(), ProcedureError> {
        self.0.send(SimCommand::Place(force_g.map(|v| v as f32))).map_err(|_| ProcedureError::SimulatedBoardStopped)
    }

    fn rest(&mut self, seconds: f64) -> Result<(), ProcedureError> {
        self.0.send(SimCommand::Elapse(seconds as f32)).map_err(|_| ProcedureError::SimulatedBoardStopped)
    }
}

/// What `accelcal thermal --sim` leaves on the board of `seed`: the chip's six-face calibration at
/// a reported 25 degC, and the temperature model learned around it while the surroundings warm at
/// 1 degC a minute over 20 degC of the die.
fn learned_on(seed: u64) -> Calibration {
    let (mut connection, board) = SimBoard::in_process(seed, SimSensor::Realistic).unwrap();
    let mut soaked = Soaked(board.controls());
    let settle_at = |soaked: &mut Soaked, reading_c: f32| {
        let target_c = board.ambient_for(reading_c);
        soaked.0.send(SimCommand::Ambient { target_c, c_per_s: f32::INFINITY }).unwrap();
        soaked.rest(2400.0).unwrap();
    };
    settle_at(&mut soaked, 25.0);
    connection.client.clear_positions().unwrap();
    for face in procedure::faces() {
        soaked.place(face.up).unwrap();
        capture_now(&mut connection, 5).unwrap();
    }
    let static_calibration = connection.client.fit_six_position().unwrap();
    settle_at(&mut soaked, 13.0);
    soaked.0.send(SimCommand::Ambient { target_c: 44.0, c_per_s: 1.0 / 60.0 }).unwrap();
    let faces = procedure::faces().iter().map(|f| f.up).collect();
    let options =
        LearnOptions { faces, capture_seconds: 5, rest_seconds: 20.0, target_span_c: 20.0, max_rounds: 10_000 };
    let mut bins = ThermalBins::default();
    learn(&mut connection, &mut soaked, &options, &mut bins, &mut |_, _| Ok(())).unwrap();
    let reference = accelcal::calibration::thermal_reference(&static_calibration);
    let fit = fit_temperature(&reference, &bins.check_span().unwrap().points()).unwrap();
    accelcal::calibration::with_temperature(&static_calibration, fit.model).unwrap()
}

/// What `accelcal thermal --sim` left on the board of `seed`, learned once for every test that asks.
fn learned(seed: u64) -> Calibration {
    static LEARNED: OnceLock<Vec<Calibration>> = OnceLock::new();
    LEARNED.get_or_init(|| (1..=SEEDS).map(learned_on).collect())[seed as usize - 1]
}

/// The worst of `values`.
fn worst(values: impl Iterator<Item = f64>) -> f64 {
    values.fold(0.0, f64::max)
}

/// The twenty sessions at `target_mg` on boards that learned their temperature model, each seed's
/// figures and their worst printed.
fn learned_sessions(target_mg: f64) -> Vec<Outcome> {
    let mut outcomes = Vec::new();
    for seed in 1..=SEEDS {
        let o = session_on(seed, SimSensor::Realistic, target_mg, Some(learned(seed)));
        println!(
            "seed {seed:2}: {} captures, board {:.1} s ({:.1} s averaging), warmed {:.2} degC; true error {:.3} mg \
             at the mean temperature, {:.3} mg at the end; verified {:.3} mg",
            o.captures, o.board_seconds, o.averaged_s, o.temp_change_c, o.at_mean_mg, o.at_end_mg, o.verified_mg
        );
        outcomes.push(o);
    }
    let (at_mean, at_end) = (worst(outcomes.iter().map(|o| o.at_mean_mg)), worst(outcomes.iter().map(|o| o.at_end_mg)));
    println!(
        "target {target_mg} mg, worst of {SEEDS} seeds: {at_mean:.3} mg at the mean temperature, {at_end:.3} mg at \
         the end; rms {:.3} and {:.3} mg; longest session {:.1} s",
        rms(outcomes.iter().map(|o| o.at_mean_mg)),
        rms(outcomes.iter().map(|o| o.at_end_mg)),
        worst(outcomes.iter().map(|o| o.board_seconds))
    );
    outcomes
}

#[test]
fn twenty_default_sessions_on_warming_boards_that_learned_their_temperature_model() {
    let outcomes = learned_sessions(TARGET_MG);
    // Measured: worst 0.221 mg at the mean temperature and 0.221 at the end (rms 0.173 and 0.173),
    // 23.7-26.8 s of averaging in sessions of 55.8-60.0 s; the session's own first-order drift left
    // 0.232 and 0.424 (rms 0.180 and 0.284).
    let longest = worst(outcomes.iter().map(|o| o.board_seconds));
    assert!(longest <= 60.0, "longest session {longest:.1} s");
    let carried = worst(outcomes.iter().map(|o| (o.at_end_mg - o.at_mean_mg).abs()));
    assert!(carried <= 0.02, "the learned model carries the calibration to the end: {carried:.3} mg apart");
    assert!(rms(outcomes.iter().map(|o| o.at_end_mg)) <= 0.2, "the stop rule aims at 0.2 mg");
}

/// Every seed within 0.2 mg, at both temperatures, is what a session aimed at 0.13 mg rms gives, in
/// about 100 s: not in one minute.
// NOTE: the fit is at its statistical limit, 9 N^2 / T for T seconds of averaging (N = 283 ug
// sqrt(s), the datasheet's noise density), so the default session's 24-27 s give 0.173 mg rms, and
// then about one seed in five lies above 0.2 mg (six of these twenty: the error's square goes as
// chi-square with nine degrees of freedom). A worst of twenty at 0.2 mg needs about 0.13 mg rms,
// 44 s of averaging, where turns at a person's pace and the verification take 33 s of the minute.
#[test]
fn every_seed_within_0_2_mg_at_both_temperatures_takes_a_target_of_0_13_mg() {
    let outcomes = learned_sessions(0.13);
    // Measured: worst 0.186 mg at the mean temperature and 0.188 at the end (rms 0.118), 55.2-60.0 s
    // of averaging in sessions of 95.1-101.2 s.
    let (at_mean, at_end) = (worst(outcomes.iter().map(|o| o.at_mean_mg)), worst(outcomes.iter().map(|o| o.at_end_mg)));
    assert!(at_mean <= TARGET_MG && at_end <= TARGET_MG, "worst {at_mean:.3} and {at_end:.3} mg");
    let longest = worst(outcomes.iter().map(|o| o.board_seconds));
    assert!(longest <= 110.0, "longest session {longest:.1} s");
}

fn rms(values: impl Iterator<Item = f64>) -> f64 {
    let (sum, n) = values.fold((0.0, 0.0), |(s, n), v| (s + v * v, n + 1.0));
    (sum / n).sqrt()
}

#[test]
fn twenty_default_sessions_on_the_warming_sensor() {
    let mut outcomes = Vec::new();
    for seed in 1..=SEEDS {
        let (o, settled) =
            (session(seed, SimSensor::Realistic, TARGET_MG), session(seed, SimSensor::Settled, TARGET_MG));
        println!(
            "seed {seed:2}: {} captures, board {:.1} s, warmed {:.2} degC; true error {:.3} mg at the end \
             ({:.3} at the mean temperature; static {:.3} and {:.3}), verified {:.3} mg; settled sensor {:.3} mg",
            o.captures,
            o.board_seconds,
            o.temp_change_c,
            o.at_end_mg,
            o.at_mean_mg,
            o.static_at_end_mg,
            o.static_at_mean_mg,
            o.verified_mg,
            settled.at_end_mg
        );
        outcomes.push((o, settled));
    }
    let at_end = rms(outcomes.iter().map(|(o, _)| o.at_end_mg));
    let at_mean = rms(outcomes.iter().map(|(o, _)| o.at_mean_mg));
    let static_end = rms(outcomes.iter().map(|(o, _)| o.static_at_end_mg));
    let settled = rms(outcomes.iter().map(|(_, s)| s.at_end_mg));
    let longest = outcomes.iter().map(|(o, _)| o.board_seconds).fold(0.0, f64::max);
    println!(
        "rms over {SEEDS} seeds: {at_end:.3} mg at the end, {at_mean:.3} mg at the mean temperature, \
              {static_end:.3} mg static, {settled:.3} mg on the settled sensor; longest session {longest:.1} s"
    );
    // Measured: longest 58.5 s; 0.182 mg at the mean temperature (0.182 settled), 0.281 mg at the
    // end against 0.735 mg static.
    assert!(longest <= 60.0, "longest session {longest:.1} s");
    assert!(settled <= 0.2, "settled sensor {settled:.3} mg rms: the stop rule aims at 0.2 mg");
    assert!(at_mean <= 0.2, "{at_mean:.3} mg rms at the mean temperature: the drift reached the nine parameters");
    assert!(at_end <= 0.45 * static_end, "fitted drift {at_end:.3} mg vs static {static_end:.3} mg at the end");
}

#[test]
fn a_looser_target_stops_no_sooner_than_the_drift_can_be_fitted() {
    // At 0.5 mg the prediction is reached after 10-11 positions; stopped there, the warming board's
    // drift stayed in the calibration (measured over 20 seeds: 0.466 mg rms at the mean temperature,
    // 0.636 mg at the end, where waiting for the drift fit gives 0.391 and 0.518 mg).
    for seed in 1..=5 {
        let o = session(seed, SimSensor::Realistic, 0.5);
        println!(
            "seed {seed}: {} captures, {:.3} mg at the mean temperature, {:.3} mg at the end",
            o.captures, o.at_mean_mg, o.at_end_mg
        );
        assert!(o.captures >= accelcal::limits::DRIFT_MIN_CAPTURES, "seed {seed}: {} captures", o.captures);
        assert!(
            o.at_end_mg < o.static_at_end_mg,
            "seed {seed}: {:.3} vs static {:.3} mg",
            o.at_end_mg,
            o.static_at_end_mg
        );
    }
}
