use nalgebra::Rotation3;

use super::*;
use crate::sim::motion::{simulate, MotionPlan};

/// A short noise-free session: the model's consistency, not its statistics.
fn noise_free(rate_hz: f64) -> MotionPlan {
    MotionPlan { rate_hz, rests: 4, noisy: false, ..MotionPlan::one_minute() }
}

#[test]
fn a_noise_free_turn_integrates_to_g_times_its_length_whatever_the_hand_does() {
    // NOTE: the noise of a turn's integral is N sqrt(D) = 283 ug sqrt(s) * sqrt(3 s) = 490 ug s,
    // its link's 0.005 deg/sqrt(Hz) / sqrt(2) * sqrt(3 s) = 1.1e-4 rad; the model must be exact far
    // below both (its only approximation the quadrature and the skew's first order).
    let session = simulate(&noise_free(1000.0), 1);
    for k in 0..session.data.turns() {
        let turn = integrate_turn(&session.truth, &session.data, k);
        let before = session.orientations[k];
        let velocity = before * turn.force_integral_gs - world_up() * turn.seconds;
        let carried = before * turn.turned.to_rotation_matrix();
        let link = (session.orientations[k + 1] * carried.inverse()).angle();
        assert!(velocity.amax() < 2e-6, "turn {k}: integral of R f dt - g D = {velocity:?} g s");
        assert!(link < 2e-6, "turn {k}: the gyro carries the rest before {link} rad off the rest after");
    }
}

#[test]
fn the_hand_really_accelerates_at_the_plans_rms() {
    // The consistency above must not hold because the hand is still: a turn's specific force in the
    // world frame departs from up by the hand's acceleration, 0.15 g rms within 1 %.
    let session = simulate(&noise_free(1000.0), 2);
    let data = &session.data;
    let range = data.turn(0);
    let mut rotation = session.orientations[0];
    let mut square = 0.0;
    for i in range.clone().skip(1) {
        let rate = session.truth.rate_rad(&data.gyro_dps[i], &session.truth.specific_force_g(&data.accel_g[i]));
        rotation *= Rotation3::new(rate / data.rate_hz);
        square += (rotation * session.truth.specific_force_g(&data.accel_g[i]) - world_up()).norm_squared();
    }
    // NOTE: the range holds the rests' last and first samples too; the hand moves over turn_s alone.
    let rms = (square / (session_plan_turn_s() * data.rate_hz)).sqrt();
    assert!((rms - 0.15).abs() < 0.0015, "the hand's rms acceleration {rms} g");
}

fn session_plan_turn_s() -> f64 {
    MotionPlan::one_minute().turn_s
}

/// A one-minute session at 200 Hz: the fit's statistics in a debug build's seconds.
fn brisk(seed: u64) -> crate::sim::motion::MotionSession {
    simulate(&MotionPlan { rate_hz: 200.0, ..MotionPlan::one_minute() }, seed)
}

/// The accelerometer's error against the truth in standard errors of `covariance`: d^T C^-1 d.
fn normalised_error(fit: &JointFit, truth: &JointModel, covariance: &nalgebra::DMatrix<f64>) -> f64 {
    let d = nalgebra::DVector::from_fn(9, |p, _| params::vector_of(&fit.model)[p] - params::vector_of(truth)[p]);
    (d.transpose() * covariance.clone().try_inverse().expect("a bound is invertible") * &d)[0]
}

#[test]
fn the_joint_fit_recovers_the_truth_within_its_standard_errors() {
    let session = brisk(3);
    let fit = fit_joint(&session.data).expect("the joint fit converges");
    let [fitted, truth] = [&fit.model, &session.truth].map(params::vector_of);
    for p in 0..params::MODEL {
        let z = (fitted[p] - truth[p]) / fit.std_errors[p];
        assert!(z.abs() < 4.5, "number {p}: {} against {} is {z} standard errors off", fitted[p], truth[p]);
    }
    assert!((fit.chi2_per_dof - 1.0).abs() < 0.3, "chi^2 per degree of freedom {}", fit.chi2_per_dof);
    assert!(fit.prediction.norm_error_mg < 0.3, "{:?}", fit.prediction);
}

#[test]
fn the_joint_fits_error_is_its_cramer_rao_bound_over_seeds() {
    // NOTE: 9 numbers over 12 seeds: the mean of d^T C^-1 d / 9 has a standard deviation of
    // sqrt(2 / 108) = 0.14 when the fit is efficient; the rms ratio is its square root.
    let seeds = 12;
    let mut sum = 0.0;
    for seed in 0..seeds {
        let session = brisk(100 + seed);
        let fit = fit_joint(&session.data).expect("the joint fit converges");
        let bound = bound(&session.truth, &session.orientations, &session.data, Information::Motion).expect("bound");
        sum += normalised_error(&fit, &session.truth, &bound.accel_covariance) / 9.0;
    }
    let ratio = (sum / seeds as f64).sqrt();
    assert!((0.75..1.2).contains(&ratio), "the error's rms is {ratio} times the bound");
}

#[test]
fn the_motion_adds_information_the_rests_lack() {
    let session = brisk(4);
    let [rests, linked, motion] = [Information::Rests, Information::GyroLinked, Information::Motion].map(|i| {
        bound(&session.truth, &session.orientations, &session.data, i).expect("bound").prediction.norm_error_mg
    });
    assert!(linked < 0.9 * rests && motion < 0.95 * linked, "rests {rests} mg, linked {linked} mg, motion {motion} mg");
}

/// A short noisy session at 100 Hz for the fallbacks (their reasons, not their statistics).
fn fallback_session() -> MotionData {
    simulate(&MotionPlan { rate_hz: 100.0, ..MotionPlan::one_minute() }, 5).data
}

/// The published part's offset, the simulated sessions' truth (`sim::motion::true_model`).
fn true_offset_g() -> nalgebra::Vector3<f64> {
    crate::sim::motion::true_model(&mut rand_xoshiro::rand_core::SeedableRng::seed_from_u64(0)).accel_offset_g
}

/// The fallback's reason, asserting that the still fit was made from the rests.
fn fallback_reason(data: &MotionData) -> Unusable {
    match fit_or_fall_back(data) {
        MotionOutcome::Still { reason, fit } => {
            // NOTE: twelve rests of 2 s: each offset's standard error is about 0.1 mg.
            let fit = (*fit).expect("twelve rests make a still fit");
            let error = nalgebra::Vector3::from(fit.offset) - true_offset_g();
            assert!(
                fit.lines_used.len() == 12 && error.amax() < 1e-3,
                "the still fit of the rests: offset off by {error:?} g"
            );
            reason
        }
        MotionOutcome::Joint(_) => panic!("the joint fit was made of unusable data"),
    }
}

#[test]
fn a_session_without_its_gyro_falls_back_to_the_still_fit_and_says_why() {
    let mut data = fallback_session();
    data.gyro_dps.clear();
    assert_eq!(fallback_reason(&data), Unusable::NoGyro);
    assert!(Unusable::NoGyro.to_string().contains("stream the gyro"));
}

#[test]
fn a_session_below_50_hz_falls_back_to_the_still_fit() {
    let data = simulate(&MotionPlan { rate_hz: 40.0, ..MotionPlan::one_minute() }, 6).data;
    assert_eq!(fallback_reason(&data), Unusable::TooSlow { rate_hz: 40.0 });
}

#[test]
fn a_session_with_lost_samples_falls_back_and_counts_them() {
    let mut data = fallback_session();
    // Three samples lost after sample 1000, one after 2000.
    data.indices.iter_mut().skip(1001).for_each(|i| *i += 3);
    data.indices.iter_mut().skip(2001).for_each(|i| *i += 1);
    assert_eq!(fallback_reason(&data), Unusable::Gaps { lost: 4, after: 1000 });
}

#[test]
fn a_clipped_session_falls_back_and_counts_the_clipped_readings() {
    let mut data = fallback_session();
    data.accel_g[3000].x = 2.0;
    data.gyro_dps[3001].z = -1000.0;
    assert_eq!(fallback_reason(&data), Unusable::Clipped { samples: 2 });
}

#[test]
fn a_usable_session_is_fitted_jointly() {
    assert_eq!(usable(&fallback_session()), Ok(()));
    assert!(matches!(fit_or_fall_back(&fallback_session()), MotionOutcome::Joint(_)));
}

#[test]
fn the_bound_of_still_rests_at_an_icosahedron_is_the_still_capture_limit() {
    // NOTE: the still-capture limit (docs/guide.md): a mean prediction variance of at least
    // 9 N^2 / T, N^2 = n^2 / 2, T the seconds of averaging; twelve rests at an icosahedron's vertices
    // spread the information as evenly as a design can, so they reach it (0.1732 mg at T = 24 s).
    let session = simulate(&MotionPlan { rate_hz: 100.0, ..MotionPlan::one_minute() }, 8);
    let seconds: f64 = session.data.rests.iter().map(|r| r.len() as f64 / session.data.rate_hz).sum();
    let limit_mg = (9.0 * session.data.noise.accel_variance_g2s() / seconds).sqrt() * 1000.0;
    let rests = bound(&session.truth, &session.orientations, &session.data, Information::Rests).expect("bound");
    let ratio = rests.prediction.norm_error_mg / limit_mg;
    assert!(
        (ratio - 1.0).abs() < 0.01,
        "rests alone {} mg against the limit {limit_mg} mg",
        rests.prediction.norm_error_mg
    );
}
