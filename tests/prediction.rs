//! The error a fit predicts at a fresh orientation, from its parameter covariance, against the
//! error its calibrations actually make there: over simulated problems of 24 rows (six of known
//! orientation) whose rows averaged 2 to 3000 samples, the RMS | |a| - g | and tilt errors at
//! fresh orientations, with the true sensor, agree with the median prediction within 30 %; and the
//! angles between the sensor's axes come out as the true sensor's.

use accelcal::data::{Dataset, Row};
use accelcal::fit::{self, axis_angles_deg, Fit, FitOptions, Model, ModelChoice};
use accelcal_tests::problem::{self, SAMPLE_STD_COUNTS, SYNTHETIC_G};
use nalgebra::{Matrix3, Vector3};
use rand_distr::{ChiSquared, Distribution};
use rand_xoshiro::rand_core::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

const PROBLEMS: u64 = 100;
/// NOTE: the bound for standard errors, applied to what they predict; 100 problems of 200
/// fresh orientations each estimate the actual RMS to a few percent.
const TOLERANCE: f64 = 0.3;

fn draw(directions: &[Vector3<f64>], seed: u64) -> Dataset {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let (sensor, offset) = (problem::sensor_matrix(), problem::sensor_offset());
    let sigma = Vector3::from(SAMPLE_STD_COUNTS);
    let rows = directions
        .iter()
        .enumerate()
        .map(|(i, up)| {
            let count = (2.0 * 1500f64.powf(i as f64 / (directions.len() - 1) as f64)).round() as u32;
            let n = f64::from(count);
            let noise = Vector3::from_fn(|k, _| sigma[k] / n.sqrt() * problem::gaussian(&mut rng));
            let spread = ChiSquared::new(n - 1.0).unwrap();
            let std = [0, 1, 2].map(|k| sigma[k] * (spread.sample(&mut rng) / (n - 1.0)).sqrt());
            let force = up * SYNTHETIC_G;
            let reference = (i % 4 == 0).then_some(force.into());
            let row = Row::new(i + 2, (sensor * force + offset + noise).into(), reference);
            Row { count: Some(count), std: Some(std), ..row }
        })
        .collect();
    Dataset { rows }
}

/// RMS | |a| - g | (mg) and tilt (degrees) of a calibration at fresh orientations of the true sensor.
fn actual(fit: &Fit, fresh: &[Vector3<f64>]) -> (f64, f64) {
    let (sensor, offset) = (problem::sensor_matrix(), problem::sensor_offset());
    let matrix = Matrix3::from_fn(|i, j| fit.matrix[i][j]);
    let fit_offset = Vector3::from(fit.offset);
    let (mut norm, mut tilt) = (0.0, 0.0);
    for u in fresh {
        let a = matrix * (sensor * u * SYNTHETIC_G + offset - fit_offset);
        norm += ((a.norm() - SYNTHETIC_G) / SYNTHETIC_G * 1000.0).powi(2);
        tilt += a.angle(u).to_degrees().powi(2);
    }
    ((norm / fresh.len() as f64).sqrt(), (tilt / fresh.len() as f64).sqrt())
}

fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

#[test]
fn predicted_norm_and_tilt_errors_match_the_actual_ones_over_100_problems() {
    let directions = problem::spread_directions(10, 7);
    let fresh = problem::spread_directions(200, 11)[14..].to_vec();
    let options = FitOptions { g: SYNTHETIC_G, ..FitOptions::default() };
    let (mut norm, mut tilt, mut predicted_norm, mut predicted_tilt) = (0.0, 0.0, Vec::new(), Vec::new());
    for seed in 0..PROBLEMS {
        let fit =
            fit::fit(&draw(&directions, 300 + seed), ModelChoice::Only(Model::ReferenceNorm12), &options).unwrap();
        let (n, t) = actual(&fit, &fresh);
        norm += n * n;
        tilt += t * t;
        let prediction = fit.prediction.expect("a prediction");
        predicted_norm.push(prediction.norm_error_mg);
        predicted_tilt.push(prediction.tilt_error_deg);
    }
    let (norm, tilt) = ((norm / PROBLEMS as f64).sqrt(), (tilt / PROBLEMS as f64).sqrt());
    let (pn, pt) = (median(predicted_norm), median(predicted_tilt));
    println!("| |a| - g |: actual {norm:.4} mg, predicted {pn:.4} mg ({:.3})", pn / norm);
    println!("tilt: actual {tilt:.5} deg, predicted {pt:.5} deg ({:.3})", pt / tilt);
    assert!((pn / norm - 1.0).abs() < TOLERANCE, "norm {pn} vs {norm}");
    assert!((pt / tilt - 1.0).abs() < TOLERANCE, "tilt {pt} vs {tilt}");
}

#[test]
fn the_axis_angles_are_the_angles_built_into_a_sensor() {
    // Axes sensing along x; 89.5 degrees from x in the x-y plane; 90.3 degrees from x in the x-z plane;
    // each with its own sensitivity (which must not matter).
    let (xy, xz) = (89.5f64.to_radians(), 90.3f64.to_radians());
    let sensor = Matrix3::from_rows(&[
        Vector3::new(1.0, 0.0, 0.0).transpose() * 16384.0,
        Vector3::new(xy.cos(), xy.sin(), 0.0).transpose() * 16000.0,
        Vector3::new(xz.cos(), 0.0, xz.sin()).transpose() * 17000.0,
    ]);
    let matrix = sensor.try_inverse().unwrap();
    let angles = axis_angles_deg(&[0, 1, 2].map(|i| [0, 1, 2].map(|j| matrix[(i, j)]))).unwrap();
    let yz = (xy.cos() * xz.cos()).acos().to_degrees();
    println!("axis angles {angles:?}, built 89.5, 90.3, {yz}");
    for (found, built) in angles.iter().zip([89.5, 90.3, yz]) {
        assert!((found - built).abs() < 1e-9, "{angles:?}");
    }
}
