//! A part drawn from the population of MPU-6050s: its static errors and its temperature drift drawn
//! from the datasheet's spreads about the published part, so that simulated boards differ as real
//! ones do (a lot, the certificate's coverage over many boards).

use rand_distr::{Distribution, StandardNormal};
use rand_xoshiro::rand_core::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

use super::Physics;

/// Standard deviation of the zero-g offset between parts, in g: the Product Specification's initial
/// calibration tolerance (rev 3.4, table 6.2: +-50 mg x and y, +-80 mg z) taken as two deviations.
const OFFSET_SPREAD_G: [f32; 3] = [25e-3, 25e-3, 40e-3];
/// Standard deviation of the sensitivity between parts: table 6.2's +-3 % as two deviations.
const SCALE_SPREAD: f32 = 0.015;
/// Standard deviation of each non-orthogonality term: table 6.2's cross-axis sensitivity of +-2 % as
/// two deviations.
const MISALIGNMENT_SPREAD: f32 = 0.01;
/// Standard deviation of the offset's drift per degC between parts, in g/degC: the datasheet's zero-g
/// change (table 6.2: +-35 mg over 0-70 degC) as 1 mg/degC, the prior the session's drift fit states.
const OFFSET_TEMPCO_SPREAD_G: f32 = 1e-3;
/// Standard deviation of the sensitivity's drift per degC: table 6.2's +-0.02 %/degC.
const SCALE_TEMPCO_SPREAD: f32 = 2e-4;
/// Mixed into the part's seed so that its draws are not the noise stream of the same seed.
const PART_STREAM: u64 = 0x5041_5254;

impl Physics {
    /// Makes this sensor a part drawn by `part_seed`: offset, sensitivity and non-orthogonality,
    /// and the first-order offset and sensitivity drift, each moved from the published part by a draw
    /// of the datasheet's spread. The noise stream is left as it was.
    pub fn drawn_part(&mut self, part_seed: u64) {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(part_seed ^ PART_STREAM);
        let mut draw = |sigma: f32| sigma * <StandardNormal as Distribution<f32>>::sample(&StandardNormal, &mut rng);
        let truth = &mut self.truth;
        for (axis, offset_spread_g) in OFFSET_SPREAD_G.into_iter().enumerate() {
            truth.offset_g[axis] += draw(offset_spread_g);
            // NOTE: M = T K with T upper unit-triangular: the diagonal carries the sensitivity, the
            // entries above it the non-orthogonality (scaled by the column's sensitivity).
            let scale = 1.0 + draw(SCALE_SPREAD);
            (0..3).for_each(|row| truth.matrix[row][axis] *= scale);
            for row in 0..axis {
                truth.matrix[row][axis] += draw(MISALIGNMENT_SPREAD) * truth.matrix[axis][axis];
            }
            self.drift.offset_g[0][axis] = draw(OFFSET_TEMPCO_SPREAD_G);
            self.drift.scale[0][axis] = draw(SCALE_TEMPCO_SPREAD);
        }
    }
}
