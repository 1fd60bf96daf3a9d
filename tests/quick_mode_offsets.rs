//! The quick mode's offset on the simulated board with a hand's 3 degree placement: the mean of the six
//! readings (the chip's six-position closed form) against per-axis pair offsets (Ferraris: o_k is
//! the k component of the mean of the +k and -k readings only), each with the same matrix, verified
//! at the same 12 fresh orientations per seed.

use std::time::Duration;

use accelcal::link::{pipe, Client};
use accelcal::procedure::{self, CollectOptions, Silent, SimulatedHand};
use accelcal::sim::SimBoard;
use firmware::sim::SimFlash;
use shared::{Calibration, Position};

const PLACEMENT_DEG: f64 = 3.0;
const WAIT: Option<Duration> = Some(Duration::from_secs(30));
const SEEDS: u64 = 6;

/// The chip's calibration with its offset replaced by the per-axis pair offsets of the six faces.
fn with_pair_offsets(chip: &Calibration, session: &accelcal::session::Session) -> Calibration {
    let reading = |position: Position| {
        let capture = session.captures.iter().find(|c| c.face == Some(position)).expect("every face captured");
        capture.stats.mean_g
    };
    let mut pair = *chip;
    for axis in 0..3 {
        let (up, down) = (reading(Position::from_axis(axis, true)), reading(Position::from_axis(axis, false)));
        pair.offset_g[axis] = (up[axis] + down[axis]) / 2.0;
    }
    pair
}

/// | |a| - 1 g | RMS in mg at 12 fresh orientations of `seed`'s hand, with `calibration` on the chip.
fn verified(
    client: &mut Client<accelcal::link::PipeEnd>,
    board: &SimBoard,
    calibration: Calibration,
    seed: u64,
) -> f64 {
    client.set_calibration(calibration).unwrap();
    let mut hand = SimulatedHand::new(board.controls(), PLACEMENT_DEG, 100 + seed);
    procedure::verify(client, &mut hand, 12, WAIT, &mut Silent { yes: true }).unwrap().after_rms_mg
}

#[test]
fn pair_offsets_against_the_mean_of_six_with_a_hands_3_degrees() {
    let (mut mean_sum, mut pair_sum) = (0.0, 0.0);
    for seed in 1..=SEEDS {
        let (host, device) = pipe();
        let board = SimBoard::spawn(device, SimFlash::new(), seed);
        let (mut client, _) = Client::connect(host).unwrap();
        let mut hand = SimulatedHand::new(board.controls(), PLACEMENT_DEG, seed);
        let options = CollectOptions { seconds: 10, wait_limit: WAIT };
        let session =
            procedure::collect(&mut client, &mut hand, &procedure::faces(), &options, &mut Silent { yes: true })
                .unwrap();
        let chip = client.fit_six_position().unwrap();
        let pair = with_pair_offsets(&chip, &session);
        let mean_mg = verified(&mut client, &board, chip, seed);
        let pair_mg = verified(&mut client, &board, pair, seed);
        println!("seed {seed}: mean of six {mean_mg:.3} mg, pair offsets {pair_mg:.3} mg");
        mean_sum += mean_mg / SEEDS as f64;
        pair_sum += pair_mg / SEEDS as f64;
    }
    println!("mean over {SEEDS} seeds: mean of six {mean_sum:.3} mg, pair offsets {pair_sum:.3} mg");
    assert!(pair_sum < mean_sum, "pair {pair_sum:.3} mg vs mean {mean_sum:.3} mg");
}
