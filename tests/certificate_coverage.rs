//! The certificate's uncertainties hold (issue 28): over 2000 simulated boards (each a part drawn by
//! its seed from the datasheet's spreads, warming after power-on, biases wandering), each calibrated by the default adaptive
//! session, the k = 2 interval of every parameter covers the sensor's true value at the session's
//! mean temperature 93-97 % of the time, and the | |a| - g | error at fresh orientations is within
//! its stated U 93-97 % of the time.

use accelcal::certificate::Certificate;
use accelcal::fit::drift;
use accelcal::session::Session;
use accelcal::sim::SimulatedSession;
use accelcal::sim::{SimBoard, SimSensor};
use firmware::sim::part::SimPart;
use firmware::sim::physics::TrueErrors;
use nalgebra::{Matrix3, Vector3};

/// NOTE: a k = 2 interval that is exactly right covers 95.45 % of the time; over N boards the
/// fraction covered scatters by sqrt(0.0455 x 0.9545 / N): 0.66 % at 1000 boards, where 97 % is only
/// 2.3 of those above, so a right interval would land above 93-97 % about once in two hundred
/// quantities (binomial; seeds 1-1000 put o_x at 97.0 %, seeds 1001-2000 at 94.9 %, with the same
/// code). At 2000 boards (0.47 %) that is about once in six thousand.
const BOARDS: u64 = 2000;
const PLACEMENT_DEG: f64 = 3.0;
/// Fresh orientations per board for the | |a| - g | check (a Fibonacci sphere).
const FRESH: usize = 50;

/// One board's default adaptive session, as `calibrate --sim` collects it, on a part drawn by the
/// seed from the datasheet's spreads.
fn session(seed: u64) -> (Session, SimBoard) {
    let (mut connection, board) = SimBoard::in_process_part((seed, SimSensor::Drawn, SimPart::mpu6050())).unwrap();
    let how = SimulatedSession { placement_deg: PLACEMENT_DEG, hand_seed: seed, target_mg: 0.2 };
    (board.collect_session(&how, &mut connection).unwrap(), board)
}

/// The true value of every parameter the certificate may state, at the die temperature TEMP_OUT
/// reads as `reading_c`: ortho9's M = T K split into T and K, o, and the offset's slope per degC.
fn true_value(board: &SimBoard, name: &str, reading_c: f32) -> f64 {
    let truth = board.truth_at(reading_c);
    let m = |i: usize, j: usize| f64::from(truth.matrix[i][j]);
    let slope = |k: usize| {
        let (up, down) = (board.truth_at(reading_c + 0.5), board.truth_at(reading_c - 0.5));
        f64::from(up.offset_g[k] - down.offset_g[k])
    };
    match name {
        "a_yz" => m(0, 1) / m(1, 1),
        "a_zy" => m(0, 2) / m(2, 2),
        "a_zx" => m(1, 2) / m(2, 2),
        "s_x" => m(0, 0),
        "s_y" => m(1, 1),
        "s_z" => m(2, 2),
        "o_x" => f64::from(truth.offset_g[0]),
        "o_y" => f64::from(truth.offset_g[1]),
        "o_z" => f64::from(truth.offset_g[2]),
        "c_x" => slope(0),
        "c_y" => slope(1),
        "c_z" => slope(2),
        other => panic!("no true value for {other}"),
    }
}

/// | |a| - 1 g | in mg at fresh orientations, the calibration M, o against the truth.
fn fresh_errors_mg(truth: &TrueErrors, matrix: &Matrix3<f64>, offset: &Vector3<f64>) -> Vec<f64> {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..FRESH)
        .map(|i| {
            let z = 1.0 - 2.0 * (i as f64 + 0.5) / FRESH as f64;
            let (r, angle) = ((1.0 - z * z).sqrt(), golden * i as f64);
            let up = [(r * angle.cos()) as f32, (r * angle.sin()) as f32, z as f32];
            let reading = Vector3::from(truth.reading_g(up).map(f64::from));
            ((matrix * (reading - offset)).norm() - 1.0).abs() * 1000.0
        })
        .collect()
}

/// One board: per parameter its error over its stated u (covered when within k = 2), and the
/// fraction of fresh orientations within the predicted | |a| - g |'s U.
struct Board {
    normalised: Vec<(String, f64)>,
    fresh_within: f64,
}

fn board(seed: u64) -> Board {
    let (session, board) = session(seed);
    let certificate = Certificate::issue(&session).unwrap();
    let reading_c = drift::mean_temp_c(&session.dataset()) as f32;
    let normalised = certificate
        .parameters
        .iter()
        .map(|(name, p)| (name.clone(), (p.value - true_value(&board, name, reading_c)) / p.u))
        .collect();
    let estimate = accelcal::certificate::Estimate::of(&session).unwrap();
    let errors = fresh_errors_mg(&board.truth_at(reading_c), &estimate.matrix, &estimate.offset);
    let bound = certificate.predicted.norm_error_mg.expanded;
    let fresh_within = errors.iter().filter(|e| **e <= bound).count() as f64 / FRESH as f64;
    Board { normalised, fresh_within }
}

#[test]
fn the_k2_intervals_cover_the_truth_93_to_97_percent_of_the_time() {
    let started = std::time::Instant::now();
    let threads = std::thread::available_parallelism().map_or(2, |n| n.get()) as u64;
    let boards: Vec<Board> = std::thread::scope(|scope| {
        let workers: Vec<_> = (0..threads)
            .map(|t| scope.spawn(move || (1..=BOARDS).filter(|s| s % threads == t).map(board).collect::<Vec<_>>()))
            .collect();
        workers.into_iter().flat_map(|w| w.join().unwrap()).collect()
    });
    let mut failures = Vec::new();
    for (k, (name, _)) in boards[0].normalised.iter().enumerate() {
        let z: Vec<f64> =
            boards.iter().filter_map(|b| b.normalised.get(k).filter(|(n, _)| n == name).map(|(_, z)| *z)).collect();
        let covered = z.iter().filter(|z| z.abs() <= 2.0).count();
        let fraction = covered as f64 / z.len() as f64;
        let rms = (z.iter().map(|z| z * z).sum::<f64>() / z.len() as f64).sqrt();
        println!("{name}: {covered} of {} boards covered ({:.1} %), rms error / u {rms:.3}", z.len(), fraction * 100.0);
        if !(0.93..=0.97).contains(&fraction) {
            failures.push(format!("{name} {:.1} %", fraction * 100.0));
        }
    }
    let fresh = boards.iter().map(|b| b.fresh_within).sum::<f64>() / boards.len() as f64;
    println!("| |a| - g | at {FRESH} fresh orientations per board within U: {:.1} %", fresh * 100.0);
    println!("{} boards in {:.1} s on {threads} threads", boards.len(), started.elapsed().as_secs_f64());
    if !(0.93..=0.97).contains(&fresh) {
        failures.push(format!("| |a| - g | {:.1} %", fresh * 100.0));
    }
    assert_eq!(boards.len() as u64, BOARDS);
    assert!(failures.is_empty(), "coverage outside 93-97 %: {failures:?}");
}
