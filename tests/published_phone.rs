//! The six-position and linear12 fits on the published phone readings (Georgieva and Hofreither).

use accelcal::data::Dataset;
use accelcal::fit::{self, FitOptions, ModelChoice};
use accelcal_tests::{data_path, phone_dataset, PHONE_G};
use nalgebra::{Matrix3, Vector3};
use shared::{Model, Position, PositionReadings};

fn options() -> FitOptions {
    FitOptions { g: PHONE_G, ..FitOptions::default() }
}

/// The published order of the six reference rows, by position.
const PUBLISHED_ORDER: [Position; 6] =
    [Position::NegX, Position::PosX, Position::NegY, Position::PosY, Position::NegZ, Position::PosZ];

/// The formula written out independently in f64 with nalgebra: X column k = (m(+k) - m(-k)) / 2g,
/// y = mean of the six, M = X^-1.
fn closed_form_f64(rows: &[[f64; 3]]) -> (Matrix3<f64>, Vector3<f64>) {
    let reading = |p: Position| Vector3::from(rows[PUBLISHED_ORDER.iter().position(|q| *q == p).unwrap()]);
    let mut x = Matrix3::zeros();
    for axis in 0..3 {
        let up = reading(Position::from_axis(axis, true));
        let down = reading(Position::from_axis(axis, false));
        x.set_column(axis, &((up - down) / (2.0 * PHONE_G)));
    }
    let y = rows[..6].iter().map(|r| Vector3::from(*r)).sum::<Vector3<f64>>() / 6.0;
    (x.try_inverse().unwrap(), y)
}

#[test]
fn on_chip_f32_six_position_agrees_with_f64_on_the_phone_data_to_1e_5_relative() {
    let dataset = phone_dataset();
    let rows: Vec<[f64; 3]> = dataset.rows.iter().map(|r| r.reading).collect();
    let mut readings = PositionReadings::<f32>::new();
    for (position, row) in PUBLISHED_ORDER.into_iter().zip(&rows) {
        readings.insert(position, row.map(|v| v as f32)).unwrap();
    }
    let chip = readings.fit(PHONE_G as f32).unwrap();
    let (matrix, offset) = closed_form_f64(&rows);

    // NOTE: relative to the largest entry: an f32 carries ~7 digits of the whole matrix, not of its
    // 1e-3 cross-axis terms taken one by one.
    let matrix_scale = matrix.amax();
    let offset_scale = offset.amax();
    for i in 0..3 {
        for j in 0..3 {
            let relative = (chip.matrix[i][j] as f64 - matrix[(i, j)]).abs() / matrix_scale;
            assert!(
                relative < 1e-5,
                "M{}{}: f32 {} vs f64 {} ({relative:.1e})",
                i + 1,
                j + 1,
                chip.matrix[i][j],
                matrix[(i, j)]
            );
        }
        let relative = (chip.offset[i] as f64 - offset[i]).abs() / offset_scale;
        assert!(relative < 1e-5, "o[{i}]: f32 {} vs f64 {} ({relative:.1e})", chip.offset[i], offset[i]);
    }
}

#[test]
fn linear12_on_the_six_axis_aligned_rows_equals_the_six_position_closed_form() {
    let mut six_rows = phone_dataset();
    six_rows.rows.truncate(6);
    let linear = fit::fit(&six_rows, ModelChoice::Only(Model::Linear12), &options()).unwrap();
    let closed = fit::fit(&six_rows, ModelChoice::Only(Model::SixPosition), &options()).unwrap();
    for i in 0..3 {
        for j in 0..3 {
            assert!((linear.matrix[i][j] - closed.matrix[i][j]).abs() < 1e-9, "M{}{}", i + 1, j + 1);
        }
        assert!((linear.offset[i] - closed.offset[i]).abs() < 1e-9, "o[{i}]");
    }
    // The same estimate has the same standard errors.
    for (a, b) in linear.parameters.iter().zip(&closed.parameters) {
        assert!((a.std_error.unwrap() - b.std_error.unwrap()).abs() < 1e-9, "{}", a.name);
    }
}

#[test]
fn six_position_calibration_improves_every_published_figure_of_merit() {
    let dataset = phone_dataset();
    let fit = fit::fit(&dataset, ModelChoice::Only(Model::SixPosition), &options()).unwrap();
    assert_eq!(fit.lines_used, [2, 3, 4, 5, 6, 7]);
    let evaluation = fit::evaluate(&dataset, &fit.matrix, &fit.offset, PHONE_G, &fit.lines_used);
    let (reference_before, reference_after) = evaluation.worst_reference_error().unwrap();
    let (norm_before, norm_after) = evaluation.worst_norm_error();
    println!("phone data, six-position fit (m/s^2):");
    println!("  worst |a - ref| of the six reference rows: before {reference_before:.4}, after {reference_after:.4}");
    println!("  worst ||a| - g| over all 13 rows:        before {norm_before:.4}, after {norm_after:.4}");
    // The six reference rows are fitted by 12 parameters from 18 equations: what is left is the
    // placement error of the phone, a few tens of mg; before, the offsets alone are over 1 m/s^2.
    assert!(reference_before > 1.0, "before {reference_before}");
    assert!(reference_after < 0.1 * reference_before, "after {reference_after}");
    assert!(norm_after < 0.5 * norm_before, "before {norm_before}, after {norm_after}");
}

#[test]
fn six_position_finds_the_six_faces_by_detection_without_references() {
    let dataset = Dataset::from_path(&data_path("huawei-phone-13.csv"), PHONE_G).unwrap();
    let detected = fit::fit(&dataset, ModelChoice::Only(Model::SixPosition), &options()).unwrap();
    let referenced = fit::fit(&phone_dataset(), ModelChoice::Only(Model::SixPosition), &options()).unwrap();
    assert_eq!(detected.model, Model::SixPosition);
    assert_eq!(detected.matrix, referenced.matrix);
    assert_eq!(detected.offset, referenced.offset);
}

#[test]
fn every_model_the_thirteen_rows_support_improves_the_norm_error() {
    let dataset = phone_dataset();
    println!("| model | rows used | worst ||a|-g| before (m/s^2) | after | rms after |");
    println!("|---|---|---|---|---|");
    for (model, result) in fit::fit_all(&dataset, &options()) {
        let fit = result.unwrap_or_else(|e| panic!("{} should fit the phone data: {e}", model.name()));
        let evaluation = fit::evaluate(&dataset, &fit.matrix, &fit.offset, PHONE_G, &fit.lines_used);
        let (before, after) = evaluation.worst_norm_error();
        let rms = evaluation.rows.iter().map(|r| r.norm_error_after.powi(2)).sum::<f64>() / 13.0;
        println!("| {} | {} | {before:.4} | {after:.4} | {:.4} |", model.name(), fit.lines_used.len(), rms.sqrt());
        assert!(after < 0.5 * before, "{}: {before} -> {after}", model.name());
    }
}
