//! `ortho9` is statistically efficient: over 200 simulated problems (24 random positions, the
//! published MPU-6050 error model, 1e-4 g of noise per averaged reading) the spread of every
//! parameter's error matches the Cramer-Rao bound within 15 %, and the mean error is within three
//! standard errors of zero.

use accelcal::data::{Dataset, Row};
use accelcal::fit::Model;
use accelcal::fit::{self, FitOptions, ModelChoice};
use firmware::sim::physics::TrueErrors;
use nalgebra::{DMatrix, Matrix3, Vector3};
use rand_distr::{Distribution, StandardNormal};
use rand_xoshiro::rand_core::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

const PROBLEMS: usize = 200;
const POSITIONS: usize = 24;
const NOISE_G: f64 = 1e-4;

/// The truth in ortho9's parameters: a_yz, a_zy, a_zx, s_x, s_y, s_z, o_x, o_y, o_z.
fn true_parameters() -> [f64; 9] {
    let truth = TrueErrors::published_mpu6050();
    let m = truth.matrix.map(|row| row.map(f64::from));
    // M = T K: s = diagonal, a_yz = M12 / s_y, a_zy = M13 / s_z, a_zx = M23 / s_z.
    let (s_x, s_y, s_z) = (m[0][0], m[1][1], m[2][2]);
    let o = truth.offset_g.map(f64::from);
    [m[0][1] / s_y, m[0][2] / s_z, m[1][2] / s_z, s_x, s_y, s_z, o[0], o[1], o[2]]
}

/// ortho9's residual |M (m - o)| - 1, written out from the published model.
fn residual(p: &[f64; 9], reading: &Vector3<f64>) -> f64 {
    let m = Matrix3::new(p[3], p[0] * p[4], p[1] * p[5], 0.0, p[4], p[2] * p[5], 0.0, 0.0, p[5]);
    (m * (reading - Vector3::new(p[6], p[7], p[8]))).norm() - 1.0
}

/// The Cramer-Rao bound of each parameter: diag of (J^T J / sigma_r^2)^-1 at the truth, with the
/// Jacobian by central differences and sigma_r the noise carried onto each residual.
fn cramer_rao(p: &[f64; 9], readings: &[Vector3<f64>]) -> [f64; 9] {
    let mut fisher = DMatrix::<f64>::zeros(9, 9);
    let m = Matrix3::new(p[3], p[0] * p[4], p[1] * p[5], 0.0, p[4], p[2] * p[5], 0.0, 0.0, p[5]);
    for reading in readings {
        let mut gradient = DMatrix::<f64>::zeros(1, 9);
        for k in 0..9 {
            let step = 1e-7;
            let (mut plus, mut minus) = (*p, *p);
            plus[k] += step;
            minus[k] -= step;
            gradient[(0, k)] = (residual(&plus, reading) - residual(&minus, reading)) / (2.0 * step);
        }
        let a = m * (reading - Vector3::new(p[6], p[7], p[8]));
        let sigma_r = NOISE_G * (m.transpose() * a.normalize()).norm();
        fisher += gradient.transpose() * gradient / (sigma_r * sigma_r);
    }
    let bound = fisher.try_inverse().expect("24 spread positions determine ortho9");
    std::array::from_fn(|k| bound[(k, k)].sqrt())
}

fn random_unit(rng: &mut Xoshiro256PlusPlus) -> Vector3<f64> {
    let mut draw = || <StandardNormal as Distribution<f64>>::sample(&StandardNormal, rng);
    Vector3::new(draw(), draw(), draw()).normalize()
}

#[test]
fn ortho9_errors_match_the_cramer_rao_bound_over_200_problems() {
    let truth = true_parameters();
    let m_true = Matrix3::new(
        truth[3],
        truth[0] * truth[4],
        truth[1] * truth[5],
        0.0,
        truth[4],
        truth[2] * truth[5],
        0.0,
        0.0,
        truth[5],
    );
    let sensor = m_true.try_inverse().unwrap();
    let offset = Vector3::new(truth[6], truth[7], truth[8]);
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(2024);
    let mut normalized: Vec<Vec<f64>> = (0..9).map(|_| Vec::with_capacity(PROBLEMS)).collect();
    for _ in 0..PROBLEMS {
        let readings: Vec<Vector3<f64>> = (0..POSITIONS)
            .map(|_| {
                let noise = Vector3::from_fn(|_, _| {
                    NOISE_G * <StandardNormal as Distribution<f64>>::sample(&StandardNormal, &mut rng)
                });
                sensor * random_unit(&mut rng) + offset + noise
            })
            .collect();
        let rows = readings.iter().enumerate().map(|(i, m)| Row::new(i + 2, [m[0], m[1], m[2]], None)).collect();
        let dataset = Dataset { rows };
        let Ok(fit) = fit::fit(&dataset, ModelChoice::Only(Model::Ortho9), &FitOptions::default()) else {
            continue; // a draw without a position near some face is refused, as it should be
        };
        let bound = cramer_rao(&truth, &readings);
        for (k, parameter) in fit.parameters.iter().enumerate() {
            normalized[k].push((parameter.value - truth[k]) / bound[k]);
        }
    }
    let names = ["a_yz", "a_zy", "a_zx", "s_x", "s_y", "s_z", "o_x", "o_y", "o_z"];
    for (name, errors) in names.iter().zip(&normalized) {
        let n = errors.len() as f64;
        assert!(n >= 190.0, "only {n} of {PROBLEMS} problems fitted");
        let mean = errors.iter().sum::<f64>() / n;
        let spread = (errors.iter().map(|e| (e - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
        println!("{name}: error spread / Cramer-Rao bound = {spread:.3}, mean error = {mean:+.3} bounds");
        assert!((spread - 1.0).abs() <= 0.15, "{name}: spread {spread:.3} of the bound");
        assert!(mean.abs() <= 3.0 * spread / n.sqrt(), "{name}: mean error {mean:.3} bounds");
    }
}
