//! The chi-square test of a fit's residuals against the noise the captures state (`count`,
//! `std_x,std_y,std_z`): data whose noise is what the file states passes, data whose noise the file
//! understates fails with a warning, and the statistic, its degrees of freedom and its p-value equal
//! an independent computation written out here (statrs for the distribution).

use accelcal::fit::Model;
use accelcal::fit::{self, Fit, FitOptions, ModelChoice, NoiseTest};
use accelcal_tests::problem::{self, SyntheticRow, SAMPLES_PER_ROW, SYNTHETIC_G};
use nalgebra::{Matrix3, Vector3};
use statrs::distribution::{ChiSquared, ContinuousCDF};

/// Relative agreement of the statistic and the p-value with the independent computation: both are
/// evaluated at the same parameters, so they agree to rounding.
const RELATIVE_TOLERANCE: f64 = 1e-9;

fn fit_only(rows: &[SyntheticRow], model: Model) -> Fit {
    let options = FitOptions { g: SYNTHETIC_G, ..FitOptions::default() };
    fit::fit(&problem::dataset(rows), ModelChoice::Only(model), &options)
        .unwrap_or_else(|e| panic!("{} should fit: {e}", model.name()))
}

/// 24 rows spread over the sphere, every fourth with its orientation, stating `std_factor` times the
/// noise they carry.
fn spread_rows(seed: u64, std_factor: f64) -> Vec<SyntheticRow> {
    problem::rows(&problem::spread_directions(10, seed), seed + 100, std_factor, |i| i % 4 == 0)
}

/// The chi-square of the residuals in the file's units: each residual over the standard deviation
/// that the stated noise of the mean reading (std / sqrt(count) per axis, carried through M) predicts
/// for it; degrees of freedom = residuals - parameters.
fn independent(model: Model, rows: &[SyntheticRow], fit: &Fit) -> NoiseTest {
    let matrix = Matrix3::from_fn(|i, j| fit.matrix[i][j]);
    let offset = Vector3::from(fit.offset);
    let (mut chi_square, mut residuals) = (0.0, 0usize);
    for row in rows {
        let sigma_mean = row.stated_std / SAMPLES_PER_ROW.sqrt();
        let covariance = matrix * Matrix3::from_diagonal(&sigma_mean.component_mul(&sigma_mean)) * matrix.transpose();
        let a = matrix * (row.reading - offset);
        match row.reference.filter(|_| model == Model::ReferenceNorm12) {
            Some(reference) => {
                chi_square += (0..3).map(|k| (a - reference)[k].powi(2) / covariance[(k, k)]).sum::<f64>();
                residuals += 3;
            }
            None => {
                let direction = a.normalize();
                chi_square += (a.norm() - SYNTHETIC_G).powi(2) / (direction.transpose() * covariance * direction)[0];
                residuals += 1;
            }
        }
    }
    let degrees_of_freedom = residuals - fit.parameters.len();
    let p_value = ChiSquared::new(degrees_of_freedom as f64).unwrap().sf(chi_square);
    NoiseTest { chi_square, degrees_of_freedom, p_value, passed: p_value >= 1e-3 }
}

fn relative(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(1e-300)
}

/// The fit's noise test, checked against the independent one; returned for the caller's claims.
fn checked_noise_test(model: Model, rows: &[SyntheticRow]) -> (Fit, NoiseTest) {
    let fit = fit_only(rows, model);
    let reported = fit.noise_test.clone().unwrap_or_else(|| panic!("{}: no noise test", model.name()));
    let expected = independent(model, rows, &fit);
    println!("{}: reported {reported:?}\n  independent {expected:?}", model.name());
    assert_eq!(reported.degrees_of_freedom, expected.degrees_of_freedom, "{}", model.name());
    assert!(relative(reported.chi_square, expected.chi_square) < RELATIVE_TOLERANCE, "{}", model.name());
    assert!(relative(reported.p_value, expected.p_value) < RELATIVE_TOLERANCE, "{}", model.name());
    (fit, reported)
}

#[test]
fn noise_as_stated_passes_with_the_independent_statistic_and_p_value() {
    // reference-norm12: 6 rows x 3 + 18 rows x 1 residuals - 12 = 24 degrees of freedom;
    // ortho9: 24 - 9 = 15.
    for (model, degrees_of_freedom) in [(Model::ReferenceNorm12, 24), (Model::Ortho9, 15)] {
        let (fit, test) = checked_noise_test(model, &spread_rows(3, 1.0));
        assert_eq!(test.degrees_of_freedom, degrees_of_freedom, "{}", model.name());
        assert!(test.passed && test.p_value > 0.01, "{}: {test:?}", model.name());
        assert!(fit.warnings.is_empty(), "{}: {:?}", model.name(), fit.warnings);
    }
}

#[test]
fn noise_understated_threefold_fails_and_the_warning_gives_the_numbers() {
    for model in [Model::ReferenceNorm12, Model::Ortho9] {
        let (fit, test) = checked_noise_test(model, &spread_rows(3, 1.0 / 3.0));
        // The statistic grows ninefold: far beyond its degrees of freedom.
        assert!(test.chi_square > 4.0 * test.degrees_of_freedom as f64, "{}: {test:?}", model.name());
        assert!(!test.passed && test.p_value < 1e-3, "{}: {test:?}", model.name());
        let expected = format!(
            "the residuals exceed what the capture noise explains (chi-square {:.1} on {} degrees of freedom, p = {:.1e})",
            test.chi_square, test.degrees_of_freedom, test.p_value
        );
        assert!(fit.warnings.iter().any(|w| w.starts_with(&expected)), "{}: {:?}", model.name(), fit.warnings);
    }
}

#[test]
fn a_model_too_simple_for_the_sensor_fails_the_test_with_the_independent_statistic() {
    // diag6 cannot represent the sensor's 1e-2 cross-axis terms: its residuals are misfit, not noise.
    let (fit, test) = checked_noise_test(Model::Diag6, &spread_rows(3, 1.0));
    assert_eq!(test.degrees_of_freedom, 18);
    assert!(!test.passed, "{test:?}");
    assert!(fit.warnings.iter().any(|w| w.contains("the model is too simple")), "{:?}", fit.warnings);
}

#[test]
fn over_forty_problems_the_statistic_averages_its_degrees_of_freedom() {
    // With the noise as stated, chi-square / dof has mean 1 and, over 40 problems of 15 degrees of
    // freedom, a standard error of sqrt(2 / 15 / 40) = 0.058: 0.2 is over three of them. A noise
    // carried without the 1 / sqrt(count) of the mean, or squared twice, is off by orders of magnitude.
    let problems = 40;
    let mut sum = 0.0;
    let mut passed = 0;
    for seed in 0..problems {
        let (_, test) = checked_noise_test(Model::Ortho9, &spread_rows(1000 + seed, 1.0));
        sum += test.chi_square / test.degrees_of_freedom as f64;
        passed += usize::from(test.passed);
    }
    let mean = sum / problems as f64;
    println!("mean chi-square / dof over {problems} problems: {mean:.3}; {passed} passed");
    assert!((mean - 1.0).abs() < 0.2, "mean chi-square / dof {mean}");
    // At the 0.001 level, at most one of 40 honest problems may fail (expected 0.04).
    assert!(passed >= problems as usize - 1, "{passed} of {problems} passed");
}

#[test]
fn the_verdict_turns_at_p_0_001_as_the_readme_states() {
    // The fit does not depend on the stated noise, so the statistic scales as 1 / factor^2: state the
    // noise so that p lands at 0.002 (passes) and at 0.0005 (fails).
    let (_, honest) = checked_noise_test(Model::Ortho9, &spread_rows(3, 1.0));
    let distribution = ChiSquared::new(honest.degrees_of_freedom as f64).unwrap();
    for (p_wanted, passes) in [(2e-3, true), (5e-4, false)] {
        let chi_square = distribution.inverse_cdf(1.0 - p_wanted);
        let factor = (honest.chi_square / chi_square).sqrt();
        let (fit, test) = checked_noise_test(Model::Ortho9, &spread_rows(3, factor));
        assert!((test.p_value / p_wanted - 1.0).abs() < 1e-3, "p {} for {p_wanted}", test.p_value);
        assert_eq!(test.passed, passes, "{test:?}");
        assert_eq!(fit.warnings.iter().any(|w| w.contains("chi-square")), !passes, "{:?}", fit.warnings);
    }
}
