//! A change of the readings' units, m -> s m + t (a shift t per axis, one scale s), changes nothing
//! a user reads: the same models accept or refuse, and every fit, mapped back, is the same with the
//! same standard errors. Raw counts of an unsigned 16-bit ADC (zero near 32768, about 4000 counts per
//! g) are the case that motivates it: the published phone set, converted, must fit like the original.

use accelcal::data::Dataset;
use accelcal::fit::{self, Fit, FitError, FitOptions, Model, ModelChoice, RICHEST_FIRST};
use accelcal_tests::{data_path, phone_dataset, PHONE_G};
use proptest::prelude::*;

/// Local gravity of the lab set (data/README.md), in m/s^2.
const LAB_G: f64 = 9.8061;

/// Relative tolerance of a parameter or standard error mapped back to the original units.
///
/// NOTE: the solver sees the same normalised problem whatever the units, so only rounding differs:
/// measured at worst 3e-9 over the cases below (the lab set's condition number is 1e4); 1e-6 leaves
/// room and still catches any unit factor, which is off by the scale itself (1e-3 to 1e4).
const RELATIVE_TOLERANCE: f64 = 1e-6;

fn lab_dataset() -> Dataset {
    accelcal::data::read_file(&data_path("ivanov-lab-32.csv"), LAB_G).expect("lab data reads")
}

/// The data set with every reading mapped m -> s m + t.
fn converted(dataset: &Dataset, scale: f64, shift: [f64; 3]) -> Dataset {
    let mut converted = dataset.clone();
    for row in &mut converted.rows {
        row.reading = [0, 1, 2].map(|k| scale * row.reading[k] + shift[k]);
        row.std = row.std.map(|s| s.map(|v| v * scale));
    }
    converted
}

/// A parameter of the converted fit in the original units: offsets o -> (o - t) / s, dimensionless
/// cross-axis terms unchanged, everything else (entries and scales of M) times s.
fn mapped_back(name: &str, value: f64, error: Option<f64>, scale: f64, shift: [f64; 3]) -> (f64, Option<f64>) {
    let axis = |name: &str| ["o_x", "o_y", "o_z"].iter().position(|n| *n == name);
    match axis(name) {
        Some(k) => ((value - shift[k]) / scale, error.map(|e| e / scale)),
        None if name.starts_with("a_") => (value, error),
        None => (value * scale, error.map(|e| e * scale)),
    }
}

fn relative(a: f64, b: f64, size: f64) -> f64 {
    (a - b).abs() / size
}

/// Largest relative difference between two fits' parameters and standard errors, each relative to
/// the largest value (or error) of its kind in the original fit.
fn largest_difference(original: &Fit, converted: &Fit, scale: f64, shift: [f64; 3]) -> f64 {
    let mut worst: f64 = 0.0;
    for (a, b) in original.parameters.iter().zip(&converted.parameters) {
        assert_eq!(a.name, b.name);
        let (value, error) = mapped_back(b.name, b.value, b.std_error, scale, shift);
        let size = a.value.abs().max(1e-3);
        worst = worst.max(relative(a.value, value, size));
        if let (Some(e), Some(f)) = (a.std_error, error) {
            worst = worst.max(relative(e, f, e));
        }
        assert_eq!(a.std_error.is_some(), error.is_some(), "{}", a.name);
    }
    worst
}

/// The same verdict for every model (and auto, when `with_auto`: it refits each model once per row),
/// and the same fits mapped back; returns the largest relative difference.
fn check_invariance(dataset: &Dataset, g: f64, (scale, shift): (f64, [f64; 3]), with_auto: bool) -> f64 {
    let options = FitOptions { g, ..FitOptions::default() };
    let other = converted(dataset, scale, shift);
    let mut worst: f64 = 0.0;
    let auto = with_auto.then_some(ModelChoice::Auto);
    let choices = RICHEST_FIRST.iter().map(|&m| ModelChoice::Only(m)).chain(auto);
    for choice in choices {
        let original = fit::fit(dataset, choice, &options);
        let changed = fit::fit(&other, choice, &options);
        match (&original, &changed) {
            (Ok(a), Ok(b)) => {
                assert_eq!(a.model, b.model, "{choice}");
                worst = worst.max(largest_difference(a, b, scale, shift));
            }
            (Err(a), Err(b)) => assert_eq!(same_kind(a), same_kind(b), "{choice}: {a} / {b}"),
            _ => panic!("{choice}: {original:?} in the original units, {changed:?} in the converted"),
        }
    }
    worst
}

fn same_kind(error: &FitError) -> String {
    format!("{error:?}").split(['{', '(']).next().unwrap_or_default().to_owned()
}

#[test]
fn the_phone_set_in_raw_counts_near_32768_fits_like_the_original() {
    // 4000 counts per g around an unsigned zero of 32768, a slightly different zero per axis; with the
    // six known orientations and, as in the file, without (faces then found from the readings).
    let scale = 4000.0 / PHONE_G;
    let shift = [32768.0, 32790.0, 32741.0];
    let without_references =
        accelcal::data::read_file(&data_path("huawei-phone-13.csv"), PHONE_G).expect("phone data reads");
    for dataset in [phone_dataset(), without_references] {
        let raw = converted(&dataset, scale, shift);
        assert!(raw.rows.iter().all(|r| r.reading.iter().all(|&v| v > 28000.0)), "every count is positive");
        let options = FitOptions { g: PHONE_G, ..FitOptions::default() };
        // The models that need no known orientation, and so must take the file as it is.
        for model in [Model::Ortho9, Model::Diag6, Model::SixPosition] {
            let fit = fit::fit(&raw, ModelChoice::Only(model), &options);
            assert!(fit.is_ok(), "{} refuses raw counts: {}", model.name(), fit.unwrap_err());
        }
        let worst = check_invariance(&dataset, PHONE_G, (scale, shift), true);
        println!("phone set in raw counts: largest relative difference {worst:.1e}");
        assert!(worst < RELATIVE_TOLERANCE, "{worst:e}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    #[test]
    fn any_change_of_units_leaves_acceptance_fits_and_errors_unchanged(
        log_scale in -3.0f64..4.0,
        shift_in_scales in prop::array::uniform3(-1e4f64..1e4),
        lab in any::<bool>(),
    ) {
        // NOTE: the shift in units of the scale: a shift of 1e4 readings' units keeps 12 of a double's
        // 16 digits for the reading itself (raw counts of 32768 at 400 counts per m/s^2 are 82 units).
        let scale = 10f64.powf(log_scale);
        let shift = shift_in_scales.map(|u| u * scale);
        let (dataset, g) = if lab { (lab_dataset(), LAB_G) } else { (phone_dataset(), PHONE_G) };
        let worst = check_invariance(&dataset, g, (scale, shift), false);
        println!("scale {scale:.3e}, lab {lab}: largest relative difference {worst:.1e}");
        prop_assert!(worst < RELATIVE_TOLERANCE, "scale {scale:e}, shift {shift:?}: {worst:e}");
    }
}

#[test]
fn five_faces_of_the_phone_set_are_refused_alike_in_any_units() {
    // Five faces only: the models that need a sixth refuse, for the same reason, in both units.
    let mut dataset = phone_dataset();
    dataset.rows.truncate(5);
    let worst = check_invariance(&dataset, PHONE_G, (4000.0 / PHONE_G, [32768.0; 3]), true);
    assert!(worst < RELATIVE_TOLERANCE, "{worst:e}");
}

#[test]
fn columns_labelled_mg_are_mg_for_raw_counts_too() {
    // The phone set in m/s^2 compares its readings with g as they stand; in raw counts the "before"
    // errors are of the readings centred and put on a nominal scale, not millions of "mg".
    let options = FitOptions { g: PHONE_G, ..FitOptions::default() };
    let original = phone_dataset();
    let raw = converted(&original, 4000.0 / PHONE_G, [32768.0, 32790.0, 32741.0]);
    let mut worst = Vec::new();
    for dataset in [&original, &raw] {
        let fit = fit::fit(dataset, ModelChoice::Only(Model::Ortho9), &options).unwrap();
        let evaluation = fit::evaluate(dataset, &fit.matrix, &fit.offset, PHONE_G, &fit.lines_used);
        let (before, after) = evaluation.worst_norm_error();
        let mg = |v: f64| v / PHONE_G * 1000.0;
        println!("nominal {}: worst before {:.2} mg, after {:.3} mg", evaluation.before_nominal, mg(before), mg(after));
        worst.push((evaluation.before_nominal, mg(before), mg(after)));
    }
    assert!(!worst[0].0 && worst[1].0);
    // The same calibration after; before, a nominal scale of the same order as the m/s^2 readings' error.
    assert!((worst[0].2 - worst[1].2).abs() < 1e-6 * worst[0].2);
    assert!(worst[1].1 > worst[1].2 && worst[1].1 < 3.0 * worst[0].1, "{worst:?}");
}
