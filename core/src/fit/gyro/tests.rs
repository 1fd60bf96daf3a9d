use nalgebra::{Matrix3, Unit, UnitQuaternion, Vector3};
use rand_distr::{Distribution, Normal};
use rand_xoshiro::rand_core::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

use super::*;

/// 100 Hz: the fit re-integrates every turn ten times an iteration, and debug builds are slow.
const INTERVAL_S: f64 = 0.01;

/// A true correction with percent-level scale errors and tenths of a degree of cross-axis terms.
fn true_correction() -> Matrix3<f64> {
    Matrix3::new(1.021, 0.004, -0.003, -0.002, 0.984, 0.005, 0.006, -0.004, 1.012)
}

/// Raw samples of a body turn by `angle_deg` about body `axis` (half-sine rate profile over one
/// second, its samples summing to the angle exactly) read through the inverse of `g`, with `bias`
/// and the noise `noise` draws.
fn turn_samples(
    axis: Vector3<f64>,
    angle_deg: f64,
    g: &Matrix3<f64>,
    bias: Vector3<f64>,
    noise: &mut dyn FnMut() -> f64,
) -> Vec<[f64; 3]> {
    let n = (1.0 / INTERVAL_S).round() as usize;
    let profile: Vec<f64> = (0..n).map(|i| ((i as f64 + 0.5) / n as f64 * std::f64::consts::PI).sin()).collect();
    let total_s: f64 = profile.iter().sum::<f64>() * INTERVAL_S;
    let raw_of = g.try_inverse().unwrap();
    profile
        .iter()
        .map(|shape| {
            let raw = raw_of * (axis * (angle_deg * shape / total_s)) + bias;
            [0, 1, 2].map(|k| raw[k] + noise())
        })
        .collect()
}

/// Turns from face to face about `axes` in turn (each skipped while it points up), `count` of them.
fn session(axes: &[usize], count: usize, noise_dps: f64, seed: u64) -> Vec<Turn> {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let normal = Normal::new(0.0, noise_dps).unwrap();
    let mut noise = move || normal.sample(&mut rng);
    let bias = Vector3::new(0.8, -1.3, 0.4);
    let mut up = Vector3::<f64>::ith((axes[0] + 1) % 3, 1.0);
    let mut turns = Vec::new();
    for &k in axes.iter().cycle() {
        if turns.len() == count {
            break;
        }
        if up[k].abs() > 0.5 {
            continue;
        }
        let sign = if turns.len() % 2 == 0 { 1.0 } else { -1.0 };
        let axis = Vector3::ith(k, 1.0);
        let rates_dps = turn_samples(axis, sign * 90.0, &true_correction(), bias, &mut noise);
        let after = UnitQuaternion::from_axis_angle(&Unit::new_normalize(axis), (sign * 90f64).to_radians())
            .inverse_transform_vector(&up);
        turns.push(Turn {
            rates_dps,
            interval_s: INTERVAL_S,
            bias_before_dps: bias.into(),
            bias_after_dps: bias.into(),
            up_before: up.into(),
            up_after: after.into(),
        });
        up = after;
    }
    turns
}

fn largest_error(fit: &GyroFit) -> f64 {
    let truth = true_correction();
    (0..9).map(|p| (fit.matrix[p / 3][p % 3] - truth[(p / 3, p % 3)]).abs()).fold(0.0, f64::max)
}

#[test]
fn turns_about_all_three_axes_recover_the_true_matrix_to_1e_6_without_noise() {
    let fit = fit_gyro(&session(&[0, 1, 2], 12, 0.0, 1)).unwrap();
    assert!(largest_error(&fit) < 1e-6, "{fit:?}");
    assert!(fit.residual_deg < 1e-4, "{}", fit.residual_deg);
}

#[test]
fn with_gyro_noise_the_error_stays_within_four_standard_errors() {
    let fit = fit_gyro(&session(&[0, 1, 2], 12, 0.3, 7)).unwrap();
    let truth = true_correction();
    for p in 0..9 {
        let (i, k) = (p / 3, p % 3);
        let (error, sigma) = ((fit.matrix[i][k] - truth[(i, k)]).abs(), fit.std_errors[i][k]);
        assert!(sigma > 1e-6 && sigma < 1e-2 && error < 4.0 * sigma, "G{i}{k}: error {error}, sigma {sigma}");
    }
}

#[test]
fn a_turn_about_two_axes_in_a_row_composes_in_the_body_frame() {
    let g = Matrix3::identity();
    let mut none = || 0.0;
    let mut rates_dps = turn_samples(Vector3::x(), 90.0, &g, Vector3::zeros(), &mut none);
    rates_dps.extend(turn_samples(Vector3::y(), 90.0, &g, Vector3::zeros(), &mut none));
    let turn = Turn {
        rates_dps,
        interval_s: INTERVAL_S,
        bias_before_dps: [0.0; 3],
        bias_after_dps: [0.0; 3],
        up_before: [0.0, 0.0, 1.0],
        up_after: [0.0; 3],
    };
    // Body turns +90 about x, then +90 about its new y: gravity ends along body -x... worked out
    // by the exact rotations.
    let exact = (UnitQuaternion::from_axis_angle(&Vector3::x_axis(), 90f64.to_radians())
        * UnitQuaternion::from_axis_angle(&Vector3::y_axis(), 90f64.to_radians()))
    .inverse_transform_vector(&Vector3::z());
    assert!((rotate_up(&turn, &g) - exact).norm() < 1e-9, "{:?} vs {exact:?}", rotate_up(&turn, &g));
}

#[test]
fn turns_all_about_one_axis_are_told_which_turns_to_add() {
    let error = fit_gyro(&session(&[2], 12, 0.0, 1)).unwrap_err();
    let GyroFitError::Unobservable { ref axes, turned_deg } = error else { panic!("{error:?}") };
    assert_eq!(axes, &vec![0, 1]);
    // The cross-axis terms of the true matrix show a few degrees on x and y, far below the need.
    assert!(turned_deg[2] > 1000.0 && turned_deg[0] < 10.0 && turned_deg[1] < 10.0, "{turned_deg:?}");
    let text = error.to_string();
    assert!(
        text.contains("add turns about the board's X axis") && text.contains("add turns about the board's Y axis"),
        "{text}"
    );
    assert!(!text.contains("board's Z axis"), "{text}");
}

#[test]
fn a_turn_about_the_vertical_counts_for_nothing() {
    let mut turn = session(&[0], 1, 0.0, 1).remove(0);
    turn.up_before = [1.0, 0.0, 0.0];
    turn.up_after = [1.0, 0.0, 0.0];
    let vertical = informative_turn_deg(&[turn.clone()]);
    turn.up_before = [0.0, 1.0, 0.0];
    let horizontal = informative_turn_deg(&[turn]);
    // The true matrix's cross-axis terms tip the axis off the vertical by tenths of a degree.
    assert!(vertical[0] < 1.0 && (horizontal[0] - 90.0 * 1.021f64.recip()).abs() < 1.0, "{vertical:?} {horizontal:?}");
}

#[test]
fn fewer_turns_than_the_fit_needs_are_refused_by_name() {
    let error = fit_gyro(&session(&[0, 1, 2], MIN_GYRO_TURNS - 1, 0.0, 1)).unwrap_err();
    assert_eq!(error, GyroFitError::TooFewTurns { turns: MIN_GYRO_TURNS - 1 });
}

/// Fits of `runs` sessions of twelve noisy turns: the scatter of each entry of G over the runs, and
/// the mean standard error the fits claimed for it.
fn scatter_and_claimed(runs: u64, noise_dps: f64) -> Vec<(f64, f64)> {
    let fits: Vec<GyroFit> =
        (0..runs).map(|seed| fit_gyro(&session(&[0, 1, 2], 12, noise_dps, 100 + seed)).unwrap()).collect();
    let n = fits.len() as f64;
    (0..9)
        .map(|p| {
            let (i, k) = (p / 3, p % 3);
            let mean = fits.iter().map(|f| f.matrix[i][k]).sum::<f64>() / n;
            let variance = fits.iter().map(|f| (f.matrix[i][k] - mean).powi(2)).sum::<f64>() / (n - 1.0);
            (variance.sqrt(), fits.iter().map(|f| f.std_errors[i][k]).sum::<f64>() / n)
        })
        .collect()
}

#[test]
fn the_standard_errors_of_g_match_its_scatter_over_repeated_sessions() {
    // 60 sessions: each entry's scatter is known to 1/sqrt(118) = 9 %, the nine pooled to about 3 %.
    let entries = scatter_and_claimed(60, 0.3);
    let ratio = (entries.iter().map(|(s, c)| (s / c).powi(2)).sum::<f64>() / 9.0).sqrt();
    assert!((0.88..1.12).contains(&ratio), "scatter / claimed standard error = {ratio:.3}: {entries:?}");
}

#[test]
fn a_turn_s_residual_with_the_true_g_is_nil_and_without_it_shows_the_scale_error() {
    // The true correction is not symmetric, so G applied transposed misses by tenths of a degree.
    let turns = session(&[0, 1, 2], 3, 0.0, 1);
    let truth = true_correction();
    let g = [0, 1, 2].map(|i| [0, 1, 2].map(|k| truth[(i, k)]));
    for turn in &turns {
        let summary = summarise_turn(turn, &g, "a", "b");
        assert!(summary.residual_calibrated_deg < 1e-4, "{summary:?}");
        assert!((summary.calibrated_deg - 90.0).abs() < 1e-4, "{summary:?}");
        assert!(summary.residual_raw_deg > 0.5, "{summary:?}");
        assert!((summary.expected_deg - 90.0).abs() < 1e-9, "{summary:?}");
    }
}
