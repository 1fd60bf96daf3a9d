//! Synthetic calibration problems from the simulated sensor's true error model: for benchmarks and
//! for checks that need many problems with a known answer.

use rand_xoshiro::rand_core::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;
use shared::linalg::Vec3;
use shared::Position;

use super::random::{gaussian, random_unit};
use crate::data::{Dataset, Row};

/// `positions` averaged readings in g of a sensor with the published MPU-6050 errors, at random
/// orientations (the six faces first when `positions` >= 6), each with `noise_g` of white noise per
/// axis; references in g on every row, or on none.
pub fn random_positions(seed: u64, positions: usize, noise_g: f64, with_references: bool) -> Dataset {
    let truth = firmware::sim::physics::TrueErrors::published_mpu6050();
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let rows = (0..positions)
        .map(|i| {
            let up: Vec3<f64> = match Position::ALL.get(i) {
                Some(face) => face.specific_force_g(),
                None => random_unit(&mut rng),
            };
            let clean = truth.reading_g(up.map(|v| v as f32)).map(f64::from);
            let reading = [0, 1, 2].map(|k| clean[k] + noise_g * gaussian(&mut rng));
            Row::new(i + 2, reading, with_references.then_some(up))
        })
        .collect();
    Dataset { rows }
}
