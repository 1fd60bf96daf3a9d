//! The three noise terms fitted to an Allan deviation curve (IEEE Std 952 Annex C):
//! AVAR(tau) = N^2 / tau + (2 ln 2 / pi) B^2 + K^2 tau / 3, for white noise N (rate / sqrt(Hz)), bias
//! instability B (the flicker floor, rate) and random walk K (rate / s / sqrt(Hz)).
//!
//! NOTE: two conventions for "noise density" differ by sqrt(2), and both are called rate / sqrt(Hz).
//! IEEE 952's N is the root of the two-sided PSD (the Allan deviation at 1 s; Kalibr's continuous-
//! time density). Datasheets give the root of the one-sided PSD, rms noise = density * sqrt(bandwidth):
//! the MPU-6050's gyro, 0.005 deg/s/sqrt(Hz) and 0.05 deg/s rms in a 100 Hz band (Product Specification
//! table 6.1). A one-sided density n puts n^2 / 2 into the two-sided PSD, so N = n / sqrt(2); the
//! report's white noise density is the datasheet's, comparable with its 400 ug/sqrt(Hz).

use nalgebra::{Matrix3, Vector3};

use super::allan::AllanPoint;
use crate::limits::{RESOLVED_FLICKER_SHARE, RESOLVED_RANDOM_WALK_SHARE};

/// The flicker floor of the Allan deviation is this times the bias instability: sqrt(2 ln 2 / pi).
// NOTE: python3 -c "import math; print(math.sqrt(2 * math.log(2) / math.pi))" (was 0.664_282_433_7, wrong
// in the eighth digit).
pub const FLICKER_FLOOR: f64 = 0.664_282_470_267_960_1;

/// The fitted noise terms of one axis, in the rate's unit (g or deg/s) and seconds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NoiseTerms {
    /// White noise N (IEEE 952, two-sided), rate / sqrt(Hz): the deviation at tau = 1 s of the -1/2 line.
    pub white_noise_n: f64,
    /// Bias instability B, rate: the flicker floor divided by [`FLICKER_FLOOR`].
    pub bias_instability: f64,
    /// Averaging time in seconds where the fitted deviation is smallest.
    pub bias_instability_tau_s: f64,
    /// Random walk K, rate / s / sqrt(Hz) (= rate / sqrt(s)): the deviation at tau = 3 s of the +1/2 line.
    pub random_walk: f64,
}

impl NoiseTerms {
    /// White noise density as datasheets state it (one-sided), rate / sqrt(Hz): sqrt(2) N.
    pub fn white_noise_density(&self) -> f64 {
        self.white_noise_n * std::f64::consts::SQRT_2
    }

    /// The fitted Allan deviation at `tau_s`.
    pub fn adev(&self, tau_s: f64) -> f64 {
        model_terms(tau_s).dot(&self.variances()).sqrt()
    }

    /// Whether a curve reaching `longest_tau_s` resolves the bias instability: the fitted deviation
    /// is smallest before the longest averaging time, and there the flicker floor is at least half of
    /// the variance. Otherwise B is what white noise and a short record leave in the fit.
    pub fn bias_instability_resolved(&self, longest_tau_s: f64) -> bool {
        let tau_s = self.bias_instability_tau_s;
        let shares = model_terms(tau_s).component_mul(&self.variances());
        let total = shares.sum();
        tau_s < longest_tau_s && total > 0.0 && shares.y >= RESOLVED_FLICKER_SHARE * total
    }

    /// Whether a curve reaching `longest_tau_s` resolves the random walk: there the K^2 tau / 3 term
    /// is at least [`RESOLVED_RANDOM_WALK_SHARE`] of the fitted variance.
    /// Otherwise K is what the other terms and a short record leave in the fit, often zero.
    pub fn random_walk_resolved(&self, longest_tau_s: f64) -> bool {
        let shares = model_terms(longest_tau_s).component_mul(&self.variances());
        let total = shares.sum();
        total > 0.0 && shares.z >= RESOLVED_RANDOM_WALK_SHARE * total
    }

    fn variances(&self) -> Vector3<f64> {
        Vector3::new(self.white_noise_n, self.bias_instability, self.random_walk).map(|v| v * v)
    }
}

/// What each squared term contributes to the Allan variance at `tau_s`.
fn model_terms(tau_s: f64) -> Vector3<f64> {
    Vector3::new(1.0 / tau_s, FLICKER_FLOOR * FLICKER_FLOOR, mutant!("random-walk-tau-2", tau_s / 3.0, tau_s / 2.0))
}

/// Fits the three terms to the curve by weighted least squares on the relative variance error, each
/// point weighted by its degrees of freedom; terms the data drive negative are fixed at zero.
/// `None` for an empty curve.
pub fn fit(curve: &[AllanPoint]) -> Option<NoiseTerms> {
    let taus: Vec<f64> = curve.iter().map(|p| p.tau_s).collect();
    let (variances, _) =
        (1u8..8).filter_map(|subset| solve_subset(curve, subset)).min_by(|a, b| a.1.total_cmp(&b.1))?;
    let [n2, b2, k2] = [variances.x, variances.y, variances.z];
    let mut terms = NoiseTerms {
        white_noise_n: n2.sqrt(),
        bias_instability: b2.sqrt(),
        bias_instability_tau_s: 0.0,
        random_walk: k2.sqrt(),
    };
    terms.bias_instability_tau_s = taus.iter().copied().min_by(|a, b| terms.adev(*a).total_cmp(&terms.adev(*b)))?;
    Some(terms)
}

/// Least squares with only the terms in the bit set `subset`; the variances and the cost, or `None`
/// when a term comes out negative or the system is singular.
fn solve_subset(curve: &[AllanPoint], subset: u8) -> Option<(Vector3<f64>, f64)> {
    let used = Vector3::from_fn(|i, _| if subset & (1 << i) != 0 { 1.0 } else { 0.0 });
    let mut normal = Matrix3::from_diagonal(&used.map(|u| 1.0 - u));
    let mut rhs = Vector3::zeros();
    for point in curve {
        let avar = point.adev * point.adev;
        let row = model_terms(point.tau_s).component_mul(&used) / avar;
        normal += row * row.transpose() * point.edf;
        rhs += row * point.edf;
    }
    let variances = normal.lu().solve(&rhs)?;
    if variances.iter().any(|v| *v < 0.0 || !v.is_finite()) {
        return None;
    }
    Some((variances, cost(curve, &variances)))
}

/// Sum over the curve of edf times the squared relative variance error.
fn cost(curve: &[AllanPoint], variances: &Vector3<f64>) -> f64 {
    curve
        .iter()
        .map(|p| {
            let relative = model_terms(p.tau_s).dot(variances) / (p.adev * p.adev) - 1.0;
            p.edf * relative * relative
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The curve IEEE Std 952 (C.2) gives for the terms, written out here rather than taken from the
    /// code under test: AVAR = N^2 / tau + (2 ln 2 / pi) B^2 + K^2 tau / 3.
    fn exact_curve(terms: &NoiseTerms) -> Vec<AllanPoint> {
        let NoiseTerms { white_noise_n: n, bias_instability: b, random_walk: k, .. } = *terms;
        let flicker = 2.0 * std::f64::consts::LN_2 / std::f64::consts::PI;
        (0..40)
            .map(|i| {
                let tau_s = 10f64.powf(i as f64 / 8.0 - 2.0);
                let adev = (n * n / tau_s + flicker * b * b + k * k * tau_s / 3.0).sqrt();
                AllanPoint { tau_s, adev, adev_low: adev, adev_high: adev, edf: 1e4 / tau_s }
            })
            .collect()
    }

    #[test]
    fn an_exact_curve_gives_back_its_terms() {
        let truth =
            NoiseTerms { white_noise_n: 4e-4, bias_instability: 4e-5, bias_instability_tau_s: 0.0, random_walk: 1e-6 };
        let fitted = fit(&exact_curve(&truth)).expect("fits");
        assert!((fitted.white_noise_n / truth.white_noise_n - 1.0).abs() < 1e-9, "{fitted:?}");
        assert!((fitted.bias_instability / truth.bias_instability - 1.0).abs() < 1e-9, "{fitted:?}");
        assert!((fitted.random_walk / truth.random_walk - 1.0).abs() < 1e-9, "{fitted:?}");
    }

    #[test]
    fn bias_instability_is_resolved_only_where_the_curve_turns_and_the_flicker_floor_dominates() {
        // NOTE: the fitted deviation is smallest near 70 s, where B holds 79 % of the variance.
        let truth =
            NoiseTerms { white_noise_n: 4e-4, bias_instability: 2e-4, bias_instability_tau_s: 0.0, random_walk: 1e-5 };
        let long = exact_curve(&truth);
        let fitted = fit(&long).expect("fits");
        assert!(fitted.bias_instability_resolved(long.last().unwrap().tau_s), "{fitted:?}");
        // The first 2.4 s of the same curve: still falling at its end, B is not resolved.
        let short = &long[..20];
        let fitted = fit(short).expect("fits");
        assert!(!fitted.bias_instability_resolved(short.last().unwrap().tau_s), "{fitted:?}");
        // White noise with a trace of flicker: the minimum is white noise's, not B's.
        let faint = NoiseTerms { bias_instability: 4e-6, random_walk: 1e-6, ..truth };
        let fitted = fit(&exact_curve(&faint)).expect("fits");
        assert!(!fitted.bias_instability_resolved(1e9), "{fitted:?}");
    }

    #[test]
    fn random_walk_is_resolved_only_where_it_holds_the_curve_s_end_and_else_bounded_from_above() {
        // NOTE: at the long curve's end (750 s) K holds 58 % of the variance; at 2.4 s under 1 %.
        let truth =
            NoiseTerms { white_noise_n: 4e-4, bias_instability: 2e-4, bias_instability_tau_s: 0.0, random_walk: 1e-5 };
        let long = exact_curve(&truth);
        let axis = |curve: &[AllanPoint]| crate::noise::AxisNoise {
            name: "accel_x",
            curve: curve.to_vec(),
            terms: fit(curve),
        };
        let resolved = axis(&long);
        assert!(resolved.random_walk_resolved(), "{:?}", resolved.terms);
        assert_eq!(resolved.random_walk_or_bound(), resolved.terms.map(|t| t.random_walk));
        let short = axis(&long[..20]);
        assert!(!short.random_walk_resolved(), "{:?}", short.terms);
        let bound = short.random_walk_or_bound().unwrap();
        let end = long[19];
        assert!((bound - end.adev * (3.0 / end.tau_s).sqrt()).abs() < 1e-15, "{bound}");
        // The bound holds the truth, as K^2 tau / 3 <= AVAR(tau) must.
        assert!(bound >= truth.random_walk, "{bound}");
    }

    #[test]
    fn pure_white_noise_fits_no_other_term() {
        let truth =
            NoiseTerms { white_noise_n: 4e-4, bias_instability: 0.0, bias_instability_tau_s: 0.0, random_walk: 0.0 };
        let fitted = fit(&exact_curve(&truth)).expect("fits");
        assert!((fitted.white_noise_n / 4e-4 - 1.0).abs() < 1e-9, "{fitted:?}");
        assert!(fitted.bias_instability < 1e-12 && fitted.random_walk < 1e-12, "{fitted:?}");
        // With only white noise the deviation keeps falling: the longest averaging time is best.
        assert!((fitted.bias_instability_tau_s - 10f64.powf(39.0 / 8.0 - 2.0)).abs() < 1e-9, "{fitted:?}");
    }

    #[test]
    fn the_terms_read_where_ieee_952_puts_them_on_the_curve() {
        // White noise alone crosses N at tau = 1 s; random walk alone crosses K at tau = 3 s; the
        // flicker floor is B sqrt(2 ln 2 / pi) = 0.6643 B.
        let only =
            |n, b, k| NoiseTerms { white_noise_n: n, bias_instability: b, bias_instability_tau_s: 0.0, random_walk: k };
        assert!((only(4e-4, 0.0, 0.0).adev(1.0) - 4e-4).abs() < 1e-15);
        assert!((only(0.0, 0.0, 2e-6).adev(3.0) - 2e-6).abs() < 1e-18);
        assert!((only(0.0, 5e-5, 0.0).adev(100.0) - 0.664_282_47 * 5e-5).abs() < 1e-13);
    }
}
