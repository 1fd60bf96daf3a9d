use super::*;

/// A small deterministic generator (64-bit LCG) so the tests need no dependency.
struct Lcg(u64);

impl Lcg {
    /// Uniform in [-1, 1).
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }

    fn direction(&mut self) -> Vec3<f64> {
        loop {
            let v = [self.next(), self.next(), self.next()];
            let n = linalg::norm(v);
            if n > 0.1 && n <= 1.0 {
                return linalg::scale(v, 1.0 / n);
            }
        }
    }
}

/// A sensor's true parameters and `count` noisy readings (noise `noise_g` per axis) from directions
/// over the sphere.
fn problem(seed: u64, count: usize, noise_g: f64) -> (Params<f64>, Vec<Vec3<f64>>) {
    let mut rng = Lcg(seed);
    let mut truth = identity::<f64>();
    for (k, value) in truth.iter_mut().enumerate() {
        *value += match k {
            0..=2 => 0.01 * rng.next(),
            3..=5 => 0.03 * rng.next(),
            _ => 0.08 * rng.next(),
        };
    }
    let inverse = linalg::inverse(&matrix_of(&truth)).unwrap();
    let offset = [truth[6], truth[7], truth[8]];
    let readings = (0..count)
        .map(|_| {
            let m = linalg::add(linalg::mul_vec(&inverse, rng.direction()), offset);
            linalg::add(m, [0, 1, 2].map(|_| noise_g * rng.next()))
        })
        .collect();
    (truth, readings)
}

#[test]
fn the_gradient_matches_finite_differences() {
    let (truth, readings) = problem(7, 1, 0.0);
    for k in 0..PARAMETERS {
        let shifted = |delta: f64| {
            let mut p = truth;
            p[k] += delta;
            residual_and_gradient(&p, readings[0]).0
        };
        let numeric = (shifted(1e-7) - shifted(-1e-7)) / 2e-7;
        let analytic = residual_and_gradient(&truth, readings[0]).1[k];
        assert!((numeric - analytic).abs() < 1e-8, "parameter {k}: {numeric} vs {analytic}");
    }
}

#[test]
fn recovers_noise_free_parameters_to_f64_rounding() {
    for seed in 0..50 {
        let (truth, readings) = problem(seed, 12, 0.0);
        let fitted = fit(&readings).unwrap();
        for (k, (got, want)) in fitted.params.iter().zip(&truth).enumerate() {
            assert!((got - want).abs() < 1e-12, "seed {seed} parameter {k}: {got} vs {want}");
        }
        assert!(fitted.cost < 1e-24, "seed {seed}: cost {}", fitted.cost);
    }
}

#[test]
fn the_f32_fit_equals_the_f64_fit_within_f32_tolerance() {
    let (mut worst_matrix, mut worst_offset) = (0.0f64, 0.0f64);
    for seed in 0..200 {
        let (_, readings) = problem(100 + seed, 14, 1e-4);
        let wide = fit(&readings).unwrap();
        let narrow: Vec<Vec3<f32>> = readings.iter().map(|m| m.map(|v| v as f32)).collect();
        let narrow = fit(&narrow).unwrap();
        let (m64, m32) = (wide.matrix(), narrow.matrix());
        for i in 0..3 {
            for j in 0..3 {
                worst_matrix = worst_matrix.max((m32[i][j] as f64 - m64[i][j]).abs());
            }
            worst_offset = worst_offset.max((narrow.offset()[i] as f64 - wide.offset()[i]).abs());
        }
    }
    // NOTE: M is near the identity, so an absolute error on M is a relative one.
    assert!(worst_matrix < 1e-4, "M differs by {worst_matrix:e}");
    assert!(worst_offset < 1e-5, "o differs by {worst_offset:e} g");
    std::println!("f32 vs f64 over 200 problems: M {worst_matrix:.2e}, o {worst_offset:.2e} g");
}

#[test]
fn refuses_too_few_readings_by_count() {
    let (_, readings) = problem(3, 8, 1e-4);
    assert_eq!(fit(&readings), Err(Ortho9Error::TooFewReadings(8)));
}

#[test]
fn refuses_readings_in_one_plane_naming_the_undetermined_parameter() {
    // Every reading has z = 0 (the board turned about z only): s_z, a_zy, a_zx and o_z are free.
    let readings: Vec<Vec3<f64>> = (0..12)
        .map(|k| {
            let angle = k as f64 * 0.5;
            [angle.cos(), angle.sin(), 0.0]
        })
        .collect();
    match fit(&readings) {
        Err(Ortho9Error::IllConditioned(k)) => assert!([1, 2, 5, 8].contains(&k), "named parameter {k}"),
        other => panic!("expected a refusal, got {other:?}"),
    }
}

#[test]
fn refuses_readings_on_a_cone_whose_scale_and_offset_along_its_axis_trade_off() {
    // The board turned about z while tilted: z reads the same everywhere, so s_z and o_z move
    // together (their scaled columns agree to rounding, a pivot of about 1e-16).
    let readings: Vec<Vec3<f64>> = (0..12)
        .map(|k| {
            let angle = k as f64 * 0.5;
            [0.8 * angle.cos(), 0.8 * angle.sin(), 0.6]
        })
        .collect();
    match fit(&readings) {
        Err(Ortho9Error::IllConditioned(k)) => assert!([5, 8].contains(&k), "named parameter {k}"),
        other => panic!("expected a refusal, got {other:?}"),
    }
}

#[test]
fn the_cholesky_refuses_a_pivot_below_the_threshold_and_names_it() {
    // Parameters 2 and 3 correlated to 1 - delta: the second pivot is about 2 delta.
    let correlated = |delta: f64| {
        let mut a = [[0.0; PARAMETERS]; PARAMETERS];
        for (k, row) in a.iter_mut().enumerate() {
            row[k] = 4.0;
        }
        (a[2][3], a[3][2]) = (4.0 * (1.0 - delta), 4.0 * (1.0 - delta));
        a
    };
    let b = [1.0; PARAMETERS];
    let threshold = min_pivot::<f64>();
    assert_eq!(normal::solve_scaled(&correlated(threshold / 4.0), &b, 0.0, threshold), Err(3));
    assert!(normal::solve_scaled(&correlated(threshold * 4.0), &b, 0.0, threshold).is_ok());
}

#[test]
fn refuses_a_reading_that_is_not_finite() {
    let (_, mut readings) = problem(5, 12, 1e-4);
    readings[4][1] = f64::NAN;
    assert_eq!(fit(&readings), Err(Ortho9Error::NotFinite));
}

#[test]
fn the_check_sees_the_start_normal_equations_and_its_refusal_ends_the_fit() {
    let (_, readings) = problem(77, 12, 1e-4);
    let mut expected = Normal::new();
    assert!(accumulate(&readings, &identity(), &mut expected));
    let mut seen = None;
    let refused = fit_checked(&readings, identity(), |normal| {
        seen = Some(*normal);
        Err(Ortho9Error::IllConditioned(4))
    });
    assert_eq!(refused, Err(Ortho9Error::IllConditioned(4)));
    assert_eq!(seen, Some(expected.jtj));
    let accepted = fit_checked(&readings, identity(), |_| Ok::<(), Ortho9Error>(()));
    assert_eq!(accepted, fit(&readings));
    assert!(accepted.is_ok());
}
