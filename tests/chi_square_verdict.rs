//! When the residuals exceed the capture noise, the warning says which of four causes the evidence
//! points to, with figures: a board that moved during a capture, known orientations placed a few
//! degrees off, noise of long averages below any real model's floor, or a model too simple.

use accelcal::data::Dataset;
use accelcal::fit::{self, Fit, FitOptions, Model, ModelChoice};
use accelcal_tests::problem::{self, SyntheticRow, SYNTHETIC_G};
use nalgebra::{Rotation3, Vector3};

fn fit_only(dataset: &Dataset, model: Model) -> Fit {
    let options = FitOptions { g: SYNTHETIC_G, ..FitOptions::default() };
    fit::fit(dataset, ModelChoice::Only(model), &options).expect("fits")
}

fn verdict(fit: &Fit) -> String {
    let warning = fit.warnings.iter().find(|w| w.contains("chi-square")).expect("a failed noise test");
    println!("{warning}");
    warning.split("p = ").nth(1).unwrap_or_default().to_owned()
}

fn spread_rows(with_reference: impl Fn(usize) -> bool) -> Vec<SyntheticRow> {
    problem::rows(&problem::spread_directions(10, 7), 3, 1.0, with_reference)
}

#[test]
fn a_row_that_scattered_three_times_the_others_is_named_as_moved() {
    let mut rows = spread_rows(|_| false);
    // Line 9 (row 8): the board rocked: its mean is off by 5 mg and its spread five times the noise.
    rows[7].reading += Vector3::new(0.0, 0.0, 5e-3 * 16384.0);
    rows[7].stated_std *= 5.0;
    let warning = verdict(&fit_only(&problem::dataset(&rows), Model::Ortho9));
    assert!(warning.contains("the board moved: line(s) 9 scatter over 3 times the others"), "{warning}");
}

#[test]
fn references_placed_two_degrees_off_are_named_with_the_angle() {
    // Each known orientation turned by 2 degrees about its own horizontal axis (a hand's placement):
    // the norms fit, the directions do not.
    let mut rows = spread_rows(|i| i < 6);
    for (i, row) in rows.iter_mut().take(6).enumerate() {
        let horizontal = row.up.cross(&Vector3::new(1.0, 2.0, 3.0 + i as f64)).normalize();
        let turn = Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(horizontal), 2f64.to_radians());
        row.reference = row.reference.map(|r| turn * r);
    }
    let warning = verdict(&fit_only(&problem::dataset(&rows), Model::ReferenceNorm12));
    let angle: f64 = warning.split("placed about ").nth(1).and_then(|s| s.split(' ').next()).unwrap().parse().unwrap();
    // NOTE: the fit absorbs the common part of the turns into M, so the RMS angle left is at most 2.
    assert!(angle > 0.5 && angle <= 2.0, "{warning}");
}

#[test]
fn long_averages_below_the_model_floor_are_not_blamed_on_the_board_or_model() {
    // 0.3 mg of unmodelled error per row (what temperature drift leaves) against a noise of long
    // averages twenty times smaller: chi-square fails, but the residuals are below any model's floor.
    let mut rows = spread_rows(|_| false);
    for (i, row) in rows.iter_mut().enumerate() {
        row.reading += row.up * (if i % 2 == 0 { 0.3e-3 } else { -0.3e-3 }) * 16384.0;
        row.stated_std /= 20.0;
    }
    let warning = verdict(&fit_only(&problem::dataset(&rows), Model::Ortho9));
    assert!(warning.contains("is below any real model's floor (1 mg)"), "{warning}");
}

#[test]
fn a_model_without_the_sensor_cross_axis_terms_is_called_too_simple_with_figures() {
    let warning = verdict(&fit_only(&problem::dataset(&spread_rows(|_| false)), Model::Diag6));
    assert!(warning.contains("the model is too simple for the sensor: | |a| - g | is "), "{warning}");
}
