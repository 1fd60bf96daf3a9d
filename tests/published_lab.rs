//! The lab fixture data of Ivanov et al.: `reference-norm12` on the first 20 rows (row 1 as +y and
//! row 10 as +z references, the other 18 as |a| = g), tested on the last 12.

use accelcal::data::Dataset;
use accelcal::fit::Model;
use accelcal::fit::{self, Fit, FitOptions, ModelChoice};
use accelcal_tests::data_path;
use nalgebra::{Matrix3, Vector3};

/// The publication's gravity, m/s^2.
const LAB_G: f64 = 9.8061;

fn lab() -> (Dataset, FitOptions) {
    let dataset = accelcal::data::read_file(&data_path("ivanov-lab-32.csv"), LAB_G).expect("lab data reads");
    let options = FitOptions {
        g: LAB_G,
        training_rows: Some((1..=20).collect()),
        reference_rows: Some(vec![1, 10]),
        ..FitOptions::default()
    };
    (dataset, options)
}

/// The residuals of the publication's objective (5), written out independently: (a - ref) / g on
/// rows 1 and 10, (|a| - g) / g on rows 2-9 and 11-20.
fn residuals(dataset: &Dataset, matrix: &Matrix3<f64>, offset: &Vector3<f64>) -> Vec<f64> {
    dataset.rows[..20]
        .iter()
        .enumerate()
        .flat_map(|(i, row)| {
            let a = matrix * (Vector3::from(row.reading) - offset);
            if i == 0 || i == 9 {
                ((a - Vector3::from(row.reference.unwrap())) / LAB_G).iter().copied().collect::<Vec<_>>()
            } else {
                vec![(a.norm() - LAB_G) / LAB_G]
            }
        })
        .collect()
}

/// The objective: the sum of the squared residuals.
fn objective(dataset: &Dataset, matrix: &Matrix3<f64>, offset: &Vector3<f64>) -> f64 {
    residuals(dataset, matrix, offset).iter().map(|r| r * r).sum()
}

fn parts(fit: &Fit) -> (Matrix3<f64>, Vector3<f64>) {
    (Matrix3::from_fn(|i, j| fit.matrix[i][j]), Vector3::from(fit.offset))
}

#[test]
fn reference_norm12_reaches_the_minimum_of_the_published_objective() {
    let (dataset, options) = lab();
    let fit = fit::fit(&dataset, ModelChoice::Only(Model::ReferenceNorm12), &options).unwrap();
    let (matrix, offset) = parts(&fit);
    let at_fit = objective(&dataset, &matrix, &offset);
    assert!((at_fit - fit.cost).abs() < 1e-12 * at_fit.max(1e-30) + 1e-18, "reported {} vs {at_fit}", fit.cost);
    // The figure of docs/measurements.md: the minimum is 3.009947e-5 (the solver's relative cost tolerance is 1e-12).
    assert!((fit.cost / 3.009947e-5 - 1.0).abs() < 1e-6, "cost {:e}", fit.cost);

    // Independent check: no step of an independent Gauss-Newton on the written-out objective, with
    // a finite-difference Jacobian in scaled parameters, lowers the cost by more than rounding.
    let scale = [matrix.amax(), matrix.amax(), matrix.amax(), 1e4];
    let mut params: Vec<f64> = matrix.iter().copied().chain(offset.iter().copied()).collect();
    let unpack = |p: &[f64]| (Matrix3::from_column_slice(&p[..9]), Vector3::new(p[9], p[10], p[11]));
    let residuals_at = |p: &[f64]| {
        let (m, o) = unpack(p);
        residuals(&dataset, &m, &o)
    };
    let mut lowest = at_fit;
    for _ in 0..5 {
        let r0 = nalgebra::DVector::from_vec(residuals_at(&params));
        let mut jacobian = nalgebra::DMatrix::zeros(r0.len(), 12);
        for k in 0..12 {
            let step = 1e-7 * if k < 9 { scale[0] } else { scale[3] };
            let mut shifted = params.clone();
            shifted[k] += step;
            let r1 = nalgebra::DVector::from_vec(residuals_at(&shifted));
            jacobian.set_column(k, &((r1 - &r0) / step));
        }
        let step = jacobian.svd(true, true).solve(&(-r0), 1e-14).unwrap();
        let candidate: Vec<f64> = params.iter().zip(step.iter()).map(|(p, s)| p + s).collect();
        let cost = residuals_at(&candidate).iter().map(|r| r * r).sum::<f64>();
        if cost < lowest {
            lowest = cost;
            params = candidate;
        }
    }
    println!("reference-norm12 on rows 1-20: cost {at_fit:.6e}, independent Gauss-Newton reached {lowest:.6e}");
    assert!(lowest > at_fit * (1.0 - 1e-6), "an independent solver went lower: {lowest:e} < {at_fit:e}");
}

#[test]
fn reference_norm12_finds_the_same_minimum_from_every_starting_point() {
    // The library starts from the data's ellipsoid; start it elsewhere by fitting the same objective
    // on copies of the data moved by known offsets and scaled by known factors: the minimum must
    // move with them exactly, and its cost must not change.
    let (dataset, options) = lab();
    let reference = fit::fit(&dataset, ModelChoice::Only(Model::ReferenceNorm12), &options).unwrap();
    for (shift, factor) in [([5e4, -3e4, 2e4], 1.0), ([0.0, 0.0, 0.0], 3.0), ([-1e5, 1e5, 0.0], 0.25)] {
        let mut moved = dataset.clone();
        for row in &mut moved.rows {
            row.reading = [0, 1, 2].map(|k| row.reading[k] * factor + shift[k]);
        }
        let fit = fit::fit(&moved, ModelChoice::Only(Model::ReferenceNorm12), &options).unwrap();
        // NOTE: the solver stops at a relative cost change of 1e-12, so that is what it promises;
        // measured 2.5e-14 to 3.6e-14.
        let relative = (fit.cost - reference.cost).abs() / reference.cost;
        assert!(relative < 1e-12, "shift {shift:?} factor {factor}: cost {} vs {}", fit.cost, reference.cost);
        // The same point: the offsets agree to 2.0e-4 count (of 1e6 per g) at worst, measured, along
        // the flat valley the missing z-down position leaves; bounded at 1.5 times that, scaled
        // with the data (the offset's own standard error is far larger: this is convergence).
        for (k, (found, shift)) in fit.offset.iter().zip(shift).enumerate() {
            let expected = reference.offset[k] * factor + shift;
            assert!((found - expected).abs() < 3e-4 * factor.max(1.0), "offset {k}: {found} vs {expected}");
        }
    }
}

#[test]
fn test_rows_have_toolface_and_inclination_errors_within_2_degrees_and_training_rows_their_measured_ones() {
    let (dataset, options) = lab();
    let fit = fit::fit(&dataset, ModelChoice::Only(Model::ReferenceNorm12), &options).unwrap();
    let evaluation = fit::evaluate(&dataset, &fit.matrix, &fit.offset, LAB_G, &fit.lines_used);
    println!("| row | set | inclination error deg | toolface error deg |");
    println!("|---|---|---|---|");
    let cell = |v: Option<f64>| v.map_or("-".to_owned(), |v| format!("{v:+.2}"));
    for (i, row) in evaluation.rows.iter().enumerate() {
        let set = if row.training { "train" } else { "test" };
        println!("| {} | {set} | {} | {} |", i + 1, cell(row.inclination_error_deg), cell(row.toolface_error_deg));
    }
    // Worst inclination and toolface errors per set, in degrees (docs/measurements.md's table). Bounds: 1.5
    // times the measured worst, except the promise of docs/measurements.md of 2 degrees on the test rows, which is
    // tighter (measured 1.73 and 1.34).
    let sets = [
        ("rows 1-10 (train)", 0..10, 0.46, 0.09, 0.69, 0.14),
        ("rows 11-20 (train)", 10..20, 1.93, 1.56, 2.9, 2.34),
        ("rows 21-32 (test)", 20..32, 1.73, 1.34, 2.0, 2.0),
    ];
    for (name, rows, measured_inclination, measured_toolface, inclination_bound, toolface_bound) in sets {
        let rows = &evaluation.rows[rows];
        assert!(rows.iter().all(|r| r.training == name.contains("train")), "{name}: training flags");
        let worst = |pick: fn(&fit::RowEvaluation) -> Option<f64>| {
            rows.iter().filter_map(pick).map(f64::abs).fold(0.0f64, f64::max)
        };
        let (inclination, toolface) = (worst(|r| r.inclination_error_deg), worst(|r| r.toolface_error_deg));
        println!("{name}: worst inclination {inclination:.2} (measured {measured_inclination}), toolface {toolface:.2} (measured {measured_toolface})");
        assert!(inclination <= inclination_bound, "{name}: inclination {inclination} degrees");
        assert!(toolface <= toolface_bound, "{name}: toolface {toolface} degrees");
    }
}
