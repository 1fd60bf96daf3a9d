//! Synthetic rate series with known noise terms, for checking the noise analysis against the truth:
//! white noise, bias instability (flicker) and random walk, in the IEEE Std 952 sense the analysis fits
//! (white noise given as datasheets give it: see `noise::fit`).

use rand_xoshiro::rand_core::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

use super::random::gaussian;

/// The true noise terms of a synthetic series, in the rate's unit and seconds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrueNoise {
    /// White noise density as datasheets state it, rate / sqrt(Hz): one-sided PSD n^2 (two-sided n^2 / 2).
    pub white_noise_density: f64,
    /// Bias instability B, rate (two-sided PSD B^2 / (2 pi f)).
    pub bias_instability: f64,
    /// Random walk K, rate / sqrt(s) (the bias drifts with variance K^2 t).
    pub random_walk: f64,
}

/// Correlation times of the first-order Gauss-Markov processes whose sum is the flicker noise: one per
/// octave, from 0.05 s to about 27 h, so the 1/f spectrum holds over every averaging time analysed.
fn flicker_correlation_times_s() -> impl Iterator<Item = f64> {
    (0..21).map(|k| 0.05 * 2f64.powi(k))
}

/// `samples` values at `rate_hz` with the given noise around `mean`, from `seed`.
pub fn noisy_series(truth: &TrueNoise, mean: f64, rate_hz: f64, samples: usize, seed: u64) -> Vec<f64> {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let dt = 1.0 / rate_hz;
    // NOTE: a sum of equal-variance Gauss-Markov processes with correlation times spaced by a ratio r
    // has the one-sided spectrum sigma^2 / (f ln r); flicker of bias instability B has B^2 / (pi f).
    let ratio: f64 = 2.0;
    let flicker_sigma = truth.bias_instability * (ratio.ln() / std::f64::consts::PI).sqrt();
    let mut flicker: Vec<(f64, f64)> =
        flicker_correlation_times_s().map(|t| ((-dt / t).exp(), flicker_sigma * gaussian(&mut rng))).collect();
    // NOTE: a one-sided density n spread over the band up to Nyquist, rate / 2: the firmware's
    // simulated sensor draws its white noise the same way.
    let white_sigma = truth.white_noise_density * (rate_hz / 2.0).sqrt();
    let walk_step = truth.random_walk * dt.sqrt();
    let mut walk = 0.0;
    (0..samples)
        .map(|_| {
            walk += walk_step * gaussian(&mut rng);
            let bias: f64 = flicker.iter_mut().map(|(a, x)| step_markov(a, x, flicker_sigma, &mut rng)).sum();
            mean + white_sigma * gaussian(&mut rng) + bias + walk
        })
        .collect()
}

/// Advances one Gauss-Markov process of stationary deviation `sigma` and returns its value.
fn step_markov(decay: &f64, value: &mut f64, sigma: f64, rng: &mut Xoshiro256PlusPlus) -> f64 {
    *value = decay * *value + sigma * (1.0 - decay * decay).sqrt() * gaussian(rng);
    *value
}
