//! The host's random draws for the simulation, in one place: Gaussians and directions.

use rand_distr::{Distribution, StandardNormal};
use rand_xoshiro::Xoshiro256PlusPlus;
use shared::linalg::{self, Vec3};

/// A standard normal draw.
pub fn gaussian(rng: &mut Xoshiro256PlusPlus) -> f64 {
    <StandardNormal as Distribution<f64>>::sample(&StandardNormal, rng)
}

/// A direction drawn uniformly over the sphere (a normalised Gaussian vector).
pub fn random_unit(rng: &mut Xoshiro256PlusPlus) -> Vec3<f64> {
    let v = [gaussian(rng), gaussian(rng), gaussian(rng)];
    linalg::scale(v, 1.0 / linalg::norm(v))
}

/// A draw uniform over [0, 1).
pub fn uniform(rng: &mut Xoshiro256PlusPlus) -> f64 {
    <rand_distr::StandardUniform as Distribution<f64>>::sample(&rand_distr::StandardUniform, rng)
}
