//! The joint fit of issue 38 over many seeds of a simulated one-minute session at 1 kHz: the
//! accelerometer's error against its Cramer-Rao bound, the bound with less information, and the
//! error against the truth at fresh orientations. `cargo run --release -p accelcal-core --features sim
//! --example motion_monte_carlo -- SEEDS [FIRST] [random]`.

use accelcal_core::fit::motion::{bound, fit_joint, Information, JointModel};
use accelcal_core::sim::motion::{simulate, MotionPlan};
use accelcal_core::sim::random::random_unit;
use nalgebra::{DVector, Matrix3, Vector3};
use rand_xoshiro::rand_core::SeedableRng;

fn main() {
    let seeds: u64 = std::env::args().nth(1).and_then(|s| s.parse().ok()).unwrap_or(200);
    let first: u64 = std::env::args().nth(2).and_then(|s| s.parse().ok()).unwrap_or(0);
    // NOTE: a third argument `random` turns about random axes in place of the designed rests.
    let spread = std::env::args().nth(3).as_deref() != Some("random");
    let plan = MotionPlan { spread, ..MotionPlan::one_minute() };
    let (mut chi, mut true_square, mut bound_square, mut worst, mut fitted) = (0.0, 0.0, 0.0, 0.0f64, 0);
    for seed in first..first + seeds {
        let session = simulate(&plan, seed);
        let Some(fit) = fit_joint(&session.data) else {
            println!("seed {seed}: the joint fit did not converge");
            continue;
        };
        fitted += 1;
        let bounds = [Information::Rests, Information::GyroLinked, Information::Motion]
            .map(|i| bound(&session.truth, &session.orientations, &session.data, i).expect("bound"));
        let motion = &bounds[2];
        let d = accel_numbers(&fit.model) - accel_numbers(&session.truth);
        chi += (d.transpose() * motion.accel_covariance.clone().try_inverse().expect("invertible") * &d)[0] / 9.0;
        let error_mg = norm_error_mg(&fit.model, &session.truth, seed);
        worst = worst.max(error_mg);
        true_square += error_mg.powi(2);
        bound_square += motion.prediction.norm_error_mg.powi(2);
        if seed < first + 3 {
            let [r, l, m] = bounds.map(|b| b.prediction.norm_error_mg);
            println!("seed {seed}: bound rests {r:.4} mg, gyro-linked {l:.4} mg, with motion {m:.4} mg; fit's own {:.4} mg, chi2/dof {:.3}, {} iterations, error {error_mg:.4} mg", fit.prediction.norm_error_mg, fit.chi2_per_dof, fit.iterations);
        }
    }
    let n = f64::from(fitted);
    println!(
        "{fitted} of {seeds} seeds fitted (from seed {first}), designed rests {spread}, 1 kHz, {} rests of {} s, {} s turns, hand {} g rms:",
        plan.rests, plan.rest_s, plan.turn_s, plan.linear_rms_g
    );
    println!(
        "  accelerometer error / Cramer-Rao bound (rms over its 9 numbers, d^T C^-1 d / 9): {:.4}",
        (chi / n).sqrt()
    );
    println!("  | |a| - g | at fresh orientations against the truth: rms {:.4} mg, worst seed {worst:.4} mg; the bound predicts {:.4} mg", (true_square / n).sqrt(), (bound_square / n).sqrt());
}

/// M's six upper entries and o.
fn accel_numbers(model: &JointModel) -> DVector<f64> {
    let m = model.accel_matrix;
    DVector::from_vec(vec![
        m[(0, 0)],
        m[(0, 1)],
        m[(0, 2)],
        m[(1, 1)],
        m[(1, 2)],
        m[(2, 2)],
        model.accel_offset_g.x,
        model.accel_offset_g.y,
        model.accel_offset_g.z,
    ])
}

/// The rms over 200 random orientations of | |a| - 1 g |, in mg, where a is the fitted calibration
/// of what the true sensor reads at 1 g.
fn norm_error_mg(fit: &JointModel, truth: &JointModel, seed: u64) -> f64 {
    let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(seed ^ 0x00f2e5);
    let sensor = truth.accel_matrix.try_inverse().unwrap_or_else(Matrix3::identity);
    let square: f64 = (0..200)
        .map(|_| {
            let u = Vector3::from(random_unit(&mut rng));
            let reading = sensor * u + truth.accel_offset_g;
            (fit.specific_force_g(&reading).norm() - 1.0).powi(2)
        })
        .sum();
    (square / 200.0).sqrt() * 1000.0
}
