//! The slow random part of the biases: a random walk plus a first-order Markov wander, per axis.
//!
//! NOTE: a first-order Markov (Gauss-Markov) wander of spread sigma is a stationary process: at any
//! moment, the moment of power-on included, its value is a draw of spread sigma. A wander started
//! at 0 would have only sigma sqrt(1 - exp(-2 t / tau)) after t seconds (a third of it 6 s after
//! power-on, two thirds after 30 s), so a board calibrated soon after power-on would wander less
//! than the bias instability it is said to have. The random walk, having no stationary spread,
//! starts at 0 at power-on.

use rand_distr::{Distribution, StandardNormal};
use rand_xoshiro::rand_core::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;
use shared::linalg::{self, Vec3};

use super::{
    Physics, ACCEL_BIAS_INSTABILITY_G, ACCEL_RANDOM_WALK_G, BIAS_CORRELATION_S, GYRO_BIAS_INSTABILITY_DPS,
    GYRO_RANDOM_WALK_DPS,
};

/// Mixed into the seed for the wander's starting point, so that drawing it leaves the noise stream
/// of the same seed as it was.
const WANDER_STREAM: u64 = 0x5741_4e44;

/// The biases' wander now.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(super) struct Wander {
    accel_walk_g: Vec3<f32>,
    accel_markov_g: Vec3<f32>,
    gyro_walk_dps: Vec3<f32>,
    gyro_markov_dps: Vec3<f32>,
}

impl Wander {
    /// The wander at power-on: each Markov wander a draw of its stationary spread (by `seed`), the
    /// random walks at 0.
    pub(super) fn stationary(seed: u64) -> Self {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed ^ WANDER_STREAM);
        let mut draw = |sigma: f32| {
            [0; 3].map(|_| sigma * <StandardNormal as Distribution<f32>>::sample(&StandardNormal, &mut rng))
        };
        Wander {
            accel_markov_g: draw(ACCEL_BIAS_INSTABILITY_G),
            gyro_markov_dps: draw(GYRO_BIAS_INSTABILITY_DPS),
            ..Wander::default()
        }
    }
}

impl Physics {
    /// What the accelerometer's bias has wandered by, in g.
    pub(super) fn accel_wander(&self) -> Vec3<f32> {
        if !(self.noisy && self.wandering) {
            return [0.0; 3];
        }
        linalg::add(self.wander.accel_walk_g, self.wander.accel_markov_g)
    }

    /// What the gyro's bias has wandered by, in deg/s.
    pub(super) fn gyro_wander(&self) -> Vec3<f32> {
        if !(self.noisy && self.wandering) {
            return [0.0; 3];
        }
        linalg::add(self.wander.gyro_walk_dps, self.wander.gyro_markov_dps)
    }

    /// Moves the random walks and the Markov wanders on by `seconds` (exact for any step).
    pub(super) fn wander_step(&mut self, seconds: f32) {
        let root = libm::sqrtf(seconds);
        let keep = libm::expf(-seconds / BIAS_CORRELATION_S);
        let fresh = libm::sqrtf(1.0 - keep * keep);
        let w = self.wander;
        let walk_a = linalg::add(w.accel_walk_g, self.noise(ACCEL_RANDOM_WALK_G * root));
        let walk_g = linalg::add(w.gyro_walk_dps, self.noise(GYRO_RANDOM_WALK_DPS * root));
        let markov_a = linalg::add(linalg::scale(w.accel_markov_g, keep), self.noise(ACCEL_BIAS_INSTABILITY_G * fresh));
        let markov_g =
            linalg::add(linalg::scale(w.gyro_markov_dps, keep), self.noise(GYRO_BIAS_INSTABILITY_DPS * fresh));
        self.wander =
            Wander { accel_walk_g: walk_a, accel_markov_g: markov_a, gyro_walk_dps: walk_g, gyro_markov_dps: markov_g };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_markov_wander_has_its_stated_spread_from_power_on_and_a_settled_sensor_none() {
        let starts: Vec<Physics> = (1..=4000).map(Physics::new).collect();
        let spread = |value: &dyn Fn(&Physics) -> f32| {
            let squares: f64 = starts.iter().map(|p| f64::from(value(p)).powi(2)).sum();
            (squares / starts.len() as f64).sqrt()
        };
        // NOTE: 4000 draws know a standard deviation to 1.1 %; 4 % is over three of those.
        let within = |found: f64, wanted: f32, what: &str| {
            assert!((found / f64::from(wanted) - 1.0).abs() < 0.04, "{what}: {found}")
        };
        within(spread(&|p| p.accel_wander()[0]), ACCEL_BIAS_INSTABILITY_G, "x accel wander at power-on, g");
        within(spread(&|p| p.accel_wander()[2]), ACCEL_BIAS_INSTABILITY_G, "z accel wander at power-on, g");
        within(spread(&|p| p.gyro_wander()[1]), GYRO_BIAS_INSTABILITY_DPS, "y gyro wander at power-on, deg/s");
        assert_eq!(Physics::settled(3).accel_wander(), [0.0; 3]);
    }
}
