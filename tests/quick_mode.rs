//! The quick calibration on the chip (issue 16; issue 11's last bullet): ten positions a hand placed
//! about 3 degrees off, fitted by the chip's own `ortho9` (f32) with no fit on the host, on the
//! realistic simulated sensor just powered on (it warms and drifts during the session), 20 seeds.
//! Its true error is the calibration against the simulated sensor's truth at the captures' mean
//! temperature (the temperature the record carries), | |M (m - o)| - 1 g | over 500 orientations
//! spread evenly over the sphere, none of them a calibration position, without noise. The chip's
//! earlier quick mode (six faces, the six-position closed form, 10 s captures) is measured beside it.

use std::time::Duration;

use accelcal::link::{pipe, Client, PipeEnd};
use accelcal::procedure::{self, CollectOptions, Silent};
use accelcal::sim::SimulatedHand;
use accelcal::sim::{Pace, SimBoard, SimSensor};
use firmware::sim::thermal::Environment;
use firmware::sim::SimFlash;
use shared::linalg;
use shared::Calibration;

const PLACEMENT_DEG: f64 = 3.0;
const WAIT: Option<Duration> = Some(Duration::from_secs(30));
const SEEDS: u64 = 20;
const FRESH: usize = 500;

/// A board of `seed` on the realistic sensor, its clock in lockstep with the requests (repeatable).
fn board(seed: u64) -> (Client<PipeEnd>, SimBoard) {
    let (host, device) = pipe();
    let board = SimBoard::spawn_with(device, SimFlash::new(), seed, SimSensor::Realistic, Pace::Lockstep);
    (Client::connect(host).unwrap().0, board)
}

/// `FRESH` directions spread evenly over the sphere (a Fibonacci lattice).
fn fresh_orientations() -> Vec<[f32; 3]> {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..FRESH)
        .map(|i| {
            let z = 1.0 - 2.0 * (i as f64 + 0.5) / FRESH as f64;
            let r = (1.0 - z * z).sqrt();
            let phi = golden * i as f64;
            [(r * phi.cos()) as f32, (r * phi.sin()) as f32, z as f32]
        })
        .collect()
}

/// RMS of | |a| - 1 g | in mg over the fresh orientations, the sensor read without noise at the
/// truth of the captures' mean temperature.
fn true_error_mg(calibration: &Calibration, board: &SimBoard) -> f64 {
    let truth = board.truth_at(calibration.mean_temp_c);
    let squares: f64 = fresh_orientations()
        .iter()
        .map(|&up| {
            let a = calibration.apply(truth.reading_g(up));
            (f64::from(linalg::norm(a)) - 1.0).powi(2)
        })
        .sum();
    (squares / FRESH as f64).sqrt() * 1000.0
}

/// Simulated seconds from power-on to the middle of a capture whose die read `reading_c`: the
/// realistic sensor's die follows 20 degC + self-heating with its time constant (firmware::sim).
fn seconds_since_power_on(reading_c: f32) -> f64 {
    let env = Environment::powered_on_at(20.0);
    let settled = f64::from(env.ambient_c + env.self_heating_c);
    let die = f64::from(reading_c - env.reading_offset_c);
    -f64::from(env.time_constant_s) * ((settled - die) / f64::from(env.self_heating_c)).ln()
}

/// The quick calibration of `seed`: the chip's fit, and the board's seconds to the end of the last
/// capture.
fn quick_on_the_chip(seed: u64) -> (accelcal::link::ChipOrtho9, f64, f64) {
    let (mut client, board) = board(seed);
    let mut hand = SimulatedHand::new(board.controls(), PLACEMENT_DEG, seed);
    let seconds = procedure::capture_seconds(true);
    let options = CollectOptions { seconds, wait_limit: WAIT };
    let targets = procedure::targets(true);
    let session = procedure::collect(&mut client, &mut hand, &targets, &options, &mut Silent { yes: true }).unwrap();
    let chip = client.fit_ortho9().unwrap();
    assert_eq!(usize::from(chip.captures), session.captures.len());
    let last = session.captures.last().unwrap().stats.temp_c;
    let board_seconds = seconds_since_power_on(last) + f64::from(seconds) / 2.0;
    (chip, true_error_mg(&chip.calibration, &board), board_seconds)
}

/// The chip's earlier quick mode on `seed`: the six faces, 10 s each, the six-position closed form.
fn six_faces_on_the_chip(seed: u64) -> f64 {
    let (mut client, board) = board(seed);
    let mut hand = SimulatedHand::new(board.controls(), PLACEMENT_DEG, seed);
    let options = CollectOptions { seconds: 10, wait_limit: WAIT };
    procedure::collect(&mut client, &mut hand, &procedure::faces(), &options, &mut Silent { yes: true }).unwrap();
    true_error_mg(&client.fit_six_position().unwrap(), &board)
}

#[test]
fn quick_on_the_chip_is_within_half_a_mg_of_the_truth_for_every_seed_with_a_hand_s_3_degrees() {
    let (mut worst, mut squares, mut old_squares, mut longest) = (0.0f64, 0.0, 0.0, 0.0f64);
    for seed in 1..=SEEDS {
        let (chip, error_mg, board_seconds) = quick_on_the_chip(seed);
        let old_mg = six_faces_on_the_chip(seed);
        println!(
            "seed {seed}: chip ortho9 {error_mg:.3} mg true error ({} captures, {} iterations, residual {:.3} mg, \
             board {board_seconds:.0} s); six faces closed form {old_mg:.2} mg",
            chip.captures, chip.iterations, chip.calibration.residual_mg
        );
        worst = worst.max(error_mg);
        longest = longest.max(board_seconds);
        squares += error_mg * error_mg / SEEDS as f64;
        old_squares += old_mg * old_mg / SEEDS as f64;
    }
    let (rms, old_rms) = (squares.sqrt(), old_squares.sqrt());
    println!("{SEEDS} seeds: quick ortho9 on the chip rms {rms:.3} mg, worst {worst:.3} mg, longest board {longest:.0} s; six faces {old_rms:.2} mg");
    // Issue 16: every seed within 0.5 mg; the old closed form trusted the placement (tens of mg).
    assert!(worst <= 0.5, "worst seed {worst:.3} mg");
    assert!(old_rms > 10.0 * rms, "six faces {old_rms:.2} mg vs ortho9 {rms:.3} mg");
}
