//! Overlapping Allan deviation of a rate series (accelerometer in g, gyro in deg/s), O(N) per averaging
//! time: the rate is integrated once ("phase" in time-and-frequency terms), then each averaging time is
//! one pass of second differences over that sum.

use statrs::distribution::{ChiSquared, ContinuousCDF, Normal};

/// Probability inside the confidence interval: one standard deviation of a normal variable.
pub const CONFIDENCE: f64 = 0.683;

/// The overlapping Allan deviation at one averaging time, with its confidence interval.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AllanPoint {
    /// Averaging time in seconds (m samples of tau0).
    pub tau_s: f64,
    /// Overlapping Allan deviation, in the rate's unit.
    pub adev: f64,
    /// Lower end of the confidence interval ([`CONFIDENCE`]), in the rate's unit.
    pub adev_low: f64,
    /// Upper end of the confidence interval, in the rate's unit.
    pub adev_high: f64,
    /// Equivalent degrees of freedom the interval was computed with.
    pub edf: f64,
}

/// Integrated rate: x\[0\] = 0, x\[k\] = tau0 * sum over i < k of (y\[i\] - mean y).
pub fn phase(rate: &[f64], tau0_s: f64) -> Vec<f64> {
    // NOTE: the mean only adds a straight line to the phase, which second differences remove; taking
    // it out first keeps the sum small, so the differences of an hour at 1 kHz keep their digits.
    let mean = rate.iter().sum::<f64>() / rate.len().max(1) as f64;
    let mut sum = 0.0;
    let mut phase = Vec::with_capacity(rate.len() + 1);
    phase.push(0.0);
    for y in rate {
        sum += (y - mean) * tau0_s;
        phase.push(sum);
    }
    phase
}

/// Averaging factors m (tau = m tau0), about `per_decade` a decade from 1 to `samples / 10`, so the
/// longest averaging time still has about a dozen degrees of freedom.
pub fn averaging_factors(samples: usize, per_decade: usize) -> Vec<usize> {
    let largest = samples / 10;
    let mut factors: Vec<usize> = (0..)
        .map(|k| 10f64.powf(k as f64 / per_decade as f64).round() as usize)
        .take_while(|&m| m <= largest)
        .collect();
    factors.dedup();
    factors
}

/// Phase values per block: every averaging factor up to this size finds its three windows of a block
/// (x0, x0 + m, x0 + 2m, 96 KiB in all) still in the core's cache from the factor before.
const BLOCK: usize = 4 * 1024;

/// Overlapping Allan variance at each averaging factor m from the phase; `None` where the phase is too
/// short for it. One sweep over the phase block by block, all factors per block, so most factors read
/// cached memory instead of the whole series each.
pub fn allan_variances(phase: &[f64], factors: &[usize], tau0_s: f64) -> Vec<Option<f64>> {
    let counts: Vec<usize> = factors.iter().map(|&m| phase.len().saturating_sub(2 * m)).collect();
    let mut energies = vec![0.0; factors.len()];
    for start in (0..phase.len()).step_by(BLOCK) {
        for ((energy, &m), &count) in energies.iter_mut().zip(factors).zip(&counts) {
            let end = count.min(start + BLOCK);
            if start < end {
                let (x0, x1, x2) = (&phase[start..end], &phase[start + m..end + m], &phase[start + 2 * m..end + 2 * m]);
                *energy += second_difference_energy(x0, x1, x2);
            }
        }
    }
    let variance = |((energy, &m), &count): ((f64, &usize), &usize)| {
        let tau_s = m as f64 * tau0_s;
        (count > 0 && m > 0).then(|| energy / (2.0 * count as f64 * tau_s * tau_s))
    };
    energies.into_iter().zip(factors).zip(&counts).map(variance).collect()
}

/// Running sums of the second-difference energy.
const LANES: usize = 8;

/// Sum of (x2 - 2 x1 + x0)^2; eight running sums let the compiler keep several vector additions in flight.
fn second_difference_energy(x0: &[f64], x1: &[f64], x2: &[f64]) -> f64 {
    let mut sums = [0.0f64; LANES];
    let chunks = x0.chunks_exact(LANES).zip(x1.chunks_exact(LANES)).zip(x2.chunks_exact(LANES));
    for ((a, b), c) in chunks {
        for k in 0..LANES {
            let d = c[k] - 2.0 * b[k] + a[k];
            sums[k] += d * d;
        }
    }
    let done = x0.len() / LANES * LANES;
    let rest: f64 = (done..x0.len()).map(|i| (x2[i] - 2.0 * x1[i] + x0[i]).powi(2)).sum();
    sums.iter().sum::<f64>() + rest
}

/// Equivalent degrees of freedom of an overlapping Allan variance for white rate noise, from
/// `phase_points` phase values at averaging factor m (the simple approximation of Howe, Allan and
/// Barnes, 1981, also allantools' `edf_simple` for alpha = 0).
pub fn white_noise_edf(phase_points: usize, m: usize) -> f64 {
    let n = phase_points as f64;
    let m = m as f64;
    let edf = (3.0 * (n - 1.0) / mutant!("allan-edf-over-m", 2.0 * m, m) - 2.0 * (n - 2.0) / n)
        * (4.0 * m * m / (4.0 * m * m + mutant!("allan-edf-plus-1", 5.0, 1.0)));
    edf.max(1.0)
}

/// Degrees of freedom above which the chi-square quantiles come from the Wilson-Hilferty cube-root
/// approximation (relative error below 1e-4 there) rather than statrs' slower iterative inverse.
const WILSON_HILFERTY_EDF: f64 = 100.0;

/// The chi-square confidence interval of a deviation with `edf` degrees of freedom: (low, high).
pub fn confidence_interval(adev: f64, edf: f64) -> (f64, f64) {
    let tail = (1.0 - CONFIDENCE) / mutant!("allan-wrong-tail", 2.0, 1.5);
    let (Some(upper), Some(lower)) = (chi_square_quantile(edf, 1.0 - tail), chi_square_quantile(edf, tail)) else {
        return (0.0, f64::INFINITY);
    };
    (adev * (edf / upper).sqrt(), adev * (edf / lower).sqrt())
}

/// The p-quantile of the chi-square distribution with `edf` degrees of freedom.
fn chi_square_quantile(edf: f64, p: f64) -> Option<f64> {
    if edf > WILSON_HILFERTY_EDF {
        let z = Normal::standard().inverse_cdf(p);
        let spread = 2.0 / (9.0 * edf);
        return Some(edf * (1.0 - spread + z * spread.sqrt()).powi(3));
    }
    Some(ChiSquared::new(edf).ok()?.inverse_cdf(p))
}

/// The overlapping Allan deviation of a rate series at the given averaging factors, with intervals.
pub fn overlapping_adev(rate: &[f64], rate_hz: f64, factors: &[usize]) -> Vec<AllanPoint> {
    let tau0_s = 1.0 / rate_hz;
    let phase = phase(rate, tau0_s);
    let variances = allan_variances(&phase, factors, tau0_s);
    factors
        .iter()
        .zip(variances)
        .filter_map(|(&m, variance)| {
            let adev = variance?.sqrt();
            let edf = white_noise_edf(phase.len(), m);
            let (adev_low, adev_high) = confidence_interval(adev, edf);
            Some(AllanPoint { tau_s: m as f64 * tau0_s, adev, adev_low, adev_high, edf })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn allan_variance_of_a_hand_computed_series() {
        // y = 1, 3, 2, 6 at tau0 = 1: phase 0, 1, 4, 6, 12 (mean 3 removed: 0, -2, -2, -3, 0).
        // m = 1: differences of successive means 2, -1, 4 -> (4 + 1 + 16) / (2 * 3).
        let phase = phase(&[1.0, 3.0, 2.0, 6.0], 1.0);
        assert_eq!(phase, vec![0.0, -2.0, -2.0, -3.0, 0.0]);
        // m = 2: 0 - 2(-2) + 0 = 4 -> 16 / (2 * 1 * 4); m = 3 needs more samples.
        assert_eq!(allan_variances(&phase, &[1, 2, 3], 1.0), vec![Some(21.0 / 6.0), Some(2.0), None]);
    }

    #[test]
    fn averaging_factors_are_log_spaced_up_to_a_tenth() {
        assert_eq!(averaging_factors(1000, 3), vec![1, 2, 5, 10, 22, 46, 100]);
    }

    #[test]
    fn the_approximate_quantiles_agree_with_the_exact_ones_where_they_take_over() {
        let edf = WILSON_HILFERTY_EDF * 1.01;
        let exact = ChiSquared::new(edf).expect("valid").inverse_cdf(0.1585);
        let approximate = chi_square_quantile(edf, 0.1585).expect("valid");
        assert!((approximate / exact - 1.0).abs() < 1e-4, "{approximate} vs {exact}");
    }

    #[test]
    fn the_interval_holds_the_deviation_and_narrows_with_more_freedom() {
        let (low, high) = confidence_interval(1.0, 10.0);
        assert!(low < 1.0 && high > 1.0, "{low} {high}");
        // For large edf the relative half-width tends to 1 / sqrt(2 edf).
        let (low, high) = confidence_interval(1.0, 20000.0);
        let half_width = (high - low) / 2.0;
        assert!((half_width - 1.0 / 200.0).abs() < 1e-4, "{half_width}");
    }

    /// allantools 2024.06's overlapping deviation, edf and interval of the series below, as printed by:
    /// python3 -c 'import numpy as np, allantools as at
    /// y = np.array([((i * 7919) % 1009) / 1009 - 0.5 for i in range(2000)])
    /// _, devs, _, _ = at.oadev(y, rate=100.0, data_type="freq", taus=[0.01, 0.1, 1.0])
    /// for m, d in zip([1, 10, 100], devs):
    ///     e = at.edf_simple(2001, m, 0); print(m, d, e, *at.confidence_interval(d, e, ci=0.683))'
    const ALLANTOOLS: [(usize, f64, f64, f64, f64); 3] = [
        (1, 0.2539184031779845, 1332.445332889111, 0.24913621908226213, 0.2589868056436688),
        (10, 0.07781386027440619, 294.3229619758022, 0.07479349949748806, 0.08123212126071454),
        (100, 0.007950852320917454, 27.99849918810124, 0.007071070896893004, 0.009268908392554927),
    ];

    #[test]
    fn deviations_and_confidence_intervals_agree_with_allantools() {
        let rate: Vec<f64> = (0..2000).map(|i| ((i * 7919) % 1009) as f64 / 1009.0 - 0.5).collect();
        let points = overlapping_adev(&rate, 100.0, &[1, 10, 100]);
        for (point, (m, adev, edf, low, high)) in points.iter().zip(ALLANTOOLS) {
            let near = |ours: f64, theirs: f64, tolerance: f64| (ours / theirs - 1.0).abs() < tolerance;
            assert!(near(point.adev, adev, 1e-9) && near(point.edf, edf, 1e-9), "m = {m}: {point:?}");
            // Above 100 degrees of freedom the quantiles are Wilson-Hilferty's, within 1e-4.
            assert!(near(point.adev_low, low, 2e-4) && near(point.adev_high, high, 2e-4), "m = {m}: {point:?}");
        }
        assert_eq!(points.len(), 3);
    }
}
