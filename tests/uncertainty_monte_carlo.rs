//! Standard errors that match reality: over 300 simulated problems of 10 and of 24 rows, each row
//! averaging between 2 and 3000 samples and stating its own sample spread (as a capture does), the
//! standard error `ortho9` reports for each parameter is within 30 % of the parameters' actual spread.
//!
//! The 10-row problem has one residual degree of freedom, as the real MPU-6050 data set of issue 11:
//! there the residual scatter alone says almost nothing (its median understates the spread by a
//! third), and the measured noise must carry the estimate.

use accelcal::data::{Dataset, Row};
use accelcal::fit::{self, Fit, FitOptions, Model, ModelChoice};
use accelcal_tests::problem::{self, SAMPLE_STD_COUNTS, SYNTHETIC_G};
use nalgebra::Vector3;
use rand_distr::{ChiSquared, Distribution};
use rand_xoshiro::rand_core::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

/// Simulated problems per row count.
const PROBLEMS: u64 = 300;
/// Largest relative difference between the median reported standard error and the actual spread.
///
/// NOTE: the spread from 300 draws is itself uncertain by 1 / sqrt(600) = 4 %; 30 % is the issue's
/// bound. Measured: see the printed ratios (docs/guide.md, "Fitting data files").
const TOLERANCE: f64 = 0.3;

/// Samples averaged by each of `rows` rows: from 2 to 3000, spaced evenly in log.
fn counts(rows: usize) -> Vec<u32> {
    (0..rows).map(|i| (2.0 * 1500f64.powf(i as f64 / (rows - 1) as f64)).round() as u32).collect()
}

/// One problem: every row's mean carries noise of std / sqrt(count), and states the standard
/// deviation its own samples would show (sigma^2 chi-square(count - 1) / (count - 1)).
fn draw(directions: &[Vector3<f64>], counts: &[u32], seed: u64) -> Dataset {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let (sensor, offset) = (problem::sensor_matrix(), problem::sensor_offset());
    let sigma = Vector3::from(SAMPLE_STD_COUNTS);
    let rows = directions
        .iter()
        .zip(counts)
        .enumerate()
        .map(|(i, (up, &count))| {
            let n = f64::from(count);
            let noise = Vector3::from_fn(|k, _| sigma[k] / n.sqrt() * problem::gaussian(&mut rng));
            let spread = ChiSquared::new(n - 1.0).expect("a chi-square of count - 1 degrees");
            let std = [0, 1, 2].map(|k| sigma[k] * (spread.sample(&mut rng) / (n - 1.0)).sqrt());
            let reading = sensor * up * SYNTHETIC_G + offset + noise;
            Row { count: Some(count), std: Some(std), ..Row::new(i + 2, reading.into(), None) }
        })
        .collect();
    Dataset { rows }
}

fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    let mid = values.len() / 2;
    if values.len().is_multiple_of(2) {
        (values[mid - 1] + values[mid]) / 2.0
    } else {
        values[mid]
    }
}

fn spread(values: &[f64]) -> f64 {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    (values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt()
}

/// For each parameter: (name, reported / actual spread, scatter-only / actual spread).
fn ratios(directions: &[Vector3<f64>]) -> Vec<(String, f64, f64)> {
    let counts = counts(directions.len());
    let options = FitOptions { g: SYNTHETIC_G, ..FitOptions::default() };
    let fits: Vec<Fit> = (0..PROBLEMS)
        .map(|seed| fit::fit(&draw(directions, &counts, 900 + seed), ModelChoice::Only(Model::Ortho9), &options))
        .map(|fit| fit.expect("ortho9 fits every simulated problem"))
        .collect();
    let column = |k: usize, pick: fn(&fit::Parameter) -> Option<f64>| -> Vec<f64> {
        fits.iter().map(|f| pick(&f.parameters[k]).expect("a standard error")).collect()
    };
    (0..fits[0].parameters.len())
        .map(|k| {
            let actual = spread(&fits.iter().map(|f| f.parameters[k].value).collect::<Vec<_>>());
            let reported = median(column(k, |p| p.std_error)) / actual;
            let scatter = median(column(k, |p| p.scatter_std_error)) / actual;
            (fits[0].parameters[k].name.to_owned(), reported, scatter)
        })
        .collect()
}

fn check(rows: usize, directions: &[Vector3<f64>]) {
    println!("ortho9, {rows} rows, {PROBLEMS} problems: median reported / actual spread (scatter alone)");
    for (name, reported, scatter) in ratios(directions) {
        println!("  {name:>4}: {reported:.3} ({scatter:.3})");
        assert!((reported - 1.0).abs() < TOLERANCE, "{rows} rows, {name}: {reported:.3}");
    }
}

#[test]
fn ten_row_standard_errors_match_the_spread_over_300_problems() {
    // The six faces and four corners: 10 norm residuals, 9 parameters, one degree of freedom.
    check(10, &problem::spread_directions(0, 0)[..10]);
}

#[test]
fn twenty_four_row_standard_errors_match_the_spread_over_300_problems() {
    check(24, &problem::spread_directions(10, 7));
}

#[test]
fn one_degree_of_freedom_and_rows_of_few_samples_are_warned_of_by_line() {
    let directions = &problem::spread_directions(0, 0)[..10];
    let counts = counts(10);
    let options = FitOptions { g: SYNTHETIC_G, ..FitOptions::default() };
    let fit = fit::fit(&draw(directions, &counts, 1), ModelChoice::Only(Model::Ortho9), &options).unwrap();
    println!("counts {counts:?}\nwarnings {:?}", fit.warnings);
    assert!(fit.warnings.iter().any(|w| w.starts_with("only 1 residual degree(s) of freedom")), "{:?}", fit.warnings);
    // Rows on lines 2, 3 and 4 averaged 2, 5 and 10 samples: fewer than 10 on the first two only.
    assert_eq!(&counts[..3], [2, 5, 10]);
    assert!(
        fit.warnings.iter().any(|w| w.starts_with("line(s) 2, 3 averaged fewer than 10 samples")),
        "{:?}",
        fit.warnings
    );
    let more =
        fit::fit(&draw(&problem::spread_directions(10, 7), &[400; 24], 1), ModelChoice::Only(Model::Ortho9), &options);
    assert!(more.unwrap().warnings.is_empty());
}

#[test]
fn weighting_rows_by_their_sample_count_narrows_every_parameters_spread() {
    // The same 300 problems of 24 rows fitted twice: weighted by count (the file carries `count` and
    // `std_*`), and unweighted (the same readings without those columns).
    let directions = problem::spread_directions(10, 7);
    let counts = counts(directions.len());
    let options = FitOptions { g: SYNTHETIC_G, ..FitOptions::default() };
    let (mut weighted, mut unweighted) = (Vec::new(), Vec::new());
    for seed in 0..PROBLEMS {
        let dataset = draw(&directions, &counts, 900 + seed);
        let mut bare = dataset.clone();
        for row in &mut bare.rows {
            (row.count, row.std) = (None, None);
        }
        let fit = |d: &Dataset| fit::fit(d, ModelChoice::Only(Model::Ortho9), &options).expect("ortho9 fits");
        weighted.push(fit(&dataset));
        unweighted.push(fit(&bare));
    }
    println!("ortho9, 24 rows: spread weighted / unweighted");
    for k in 0..weighted[0].parameters.len() {
        let values = |fits: &[Fit]| spread(&fits.iter().map(|f| f.parameters[k].value).collect::<Vec<_>>());
        let ratio = values(&weighted) / values(&unweighted);
        println!("  {:>4}: {ratio:.3}", weighted[0].parameters[k].name);
        assert!(ratio < 0.9, "{}: {ratio:.3}", weighted[0].parameters[k].name);
    }
}
