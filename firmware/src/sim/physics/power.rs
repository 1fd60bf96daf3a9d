//! A power cycle of the simulated sensor: a fresh noise stream for each power-on and, where asked
//! for, the turn-on bias repeatability of a real part (its offset differs a little at every power-on).

use rand_distr::{Distribution, StandardNormal};

use super::Physics;
use shared::linalg;

impl Physics {
    /// The sensor as it is at its `cycle`-th power-on (0: the first): its noise from an independent
    /// stream of the same seed (2^128 draws apart), and each offset moved by a draw of standard
    /// deviation `turn_on_bias_g` (g; 0: none). Without both, the sensor is exactly as created.
    pub fn power_on(&mut self, cycle: u64, turn_on_bias_g: f32) {
        for _ in 0..cycle {
            self.rng.jump();
        }
        if turn_on_bias_g > 0.0 {
            let mut draw =
                || turn_on_bias_g * <StandardNormal as Distribution<f32>>::sample(&StandardNormal, &mut self.rng);
            let bias = [draw(), draw(), draw()];
            self.truth.offset_g = linalg::add(self.truth.offset_g, bias);
        }
    }
}
