//! `auto` chooses by evidence: the model whose fits best predict the rows they did not see
//! (leave-one-out), each figure checked here against refits through the public row selection; and
//! where nothing fits, it names the model the data came closest to and what to add.
//!
//! The tool does not refit once per row (that made `fit` quadratic in rows): it moves the solution
//! by each row's influence (exact for `linear12`, the Gauss-Newton step for the nonlinear models) and
//! refits only the rows the fit hangs on. Its figures agree with the refits to [`AGREEMENT`].

use accelcal::data::Dataset;
use accelcal::fit::{self, FitError, FitOptions, ModelChoice, RICHEST_FIRST};
use accelcal_tests::problem::{dataset, rows, spread_directions, SYNTHETIC_G};
use accelcal_tests::{data_path, phone_dataset, PHONE_G};

/// Local gravity of the lab set (data/README.md), in m/s^2.
const LAB_G: f64 = 9.8061;
/// Largest relative difference allowed between the tool's leave-one-out RMS and the refits'.
/// NOTE: the one-step change is exact for a linear problem; for | |a| - g | it leaves the second
/// order of a change of about one residual (1e-4 of g here) divided by 1 - leverage.
const AGREEMENT: f64 = 1e-3;

/// The leave-one-out RMS of | |a| - g | computed with `training_rows`: row i evaluated by the fit to
/// all the others; `None` when some refit is refused.
fn independent_leave_one_out(dataset: &Dataset, choice: ModelChoice, g: f64) -> Option<f64> {
    let n = dataset.rows.len();
    let mut sum = 0.0;
    for left_out in 1..=n {
        let training_rows = Some((1..=n).filter(|&r| r != left_out).collect());
        let options = FitOptions { g, training_rows, ..FitOptions::default() };
        let fit = fit::fit(dataset, choice, &options).ok()?;
        let evaluation = fit::evaluate(dataset, &fit.matrix, &fit.offset, g, &fit.lines_used);
        sum += evaluation.rows[left_out - 1].norm_error_after.powi(2);
    }
    Some((sum / n as f64).sqrt())
}

/// The model the richest-first rule of before would have chosen.
fn richest_that_fits(dataset: &Dataset, options: &FitOptions) -> &'static str {
    let fits = |m| fit::fit(dataset, ModelChoice::Only(m), options).is_ok();
    RICHEST_FIRST.into_iter().find(|&m| fits(m)).map_or("none", |m| m.name())
}

fn check_choice(name: &str, dataset: &Dataset, g: f64) {
    let options = FitOptions { g, ..FitOptions::default() };
    let fit = fit::fit(dataset, ModelChoice::Auto, &options).expect("auto fits");
    let selection = fit.selection.as_ref().expect("auto says why");
    println!("{name}: auto chose {} (richest-first: {})", fit.model.name(), richest_that_fits(dataset, &options));
    let mut best = (f64::INFINITY, "none");
    for (model, (reported_name, reported)) in RICHEST_FIRST.into_iter().zip(&selection.leave_one_out) {
        assert_eq!(model.name(), *reported_name);
        let independent = independent_leave_one_out(dataset, ModelChoice::Only(model), g);
        println!("  {:>16}: {:?} mg", model.name(), reported.map(|v| v / g * 1000.0));
        match (reported, independent) {
            (Some(r), Some(i)) => {
                println!(
                    "  {:>16}: refits {:.6} mg, relative difference {:.1e}",
                    "",
                    i / g * 1000.0,
                    (r - i).abs() / i
                );
                assert!((r - i).abs() <= AGREEMENT * i, "{}: {r} vs {i}", model.name());
            }
            (r, i) => assert_eq!(r.is_some(), i.is_some(), "{}: {r:?} vs {i:?}", model.name()),
        }
        if let Some(r) = reported.filter(|&r| r < best.0) {
            best = (r, model.name());
        }
    }
    assert_eq!(fit.model.name(), best.1, "{}", selection.reason);
    assert!(selection.reason.starts_with(&format!("{} predicts rows it did not see best", best.1)));
}

#[test]
fn auto_chooses_the_smallest_leave_one_out_error_on_the_published_sets() {
    let phone_file = accelcal::data::read_file(&data_path("huawei-phone-13.csv"), PHONE_G).expect("phone data reads");
    check_choice("phone file", &phone_file, PHONE_G);
    check_choice("phone with six known orientations", &phone_dataset(), PHONE_G);
    let lab = accelcal::data::read_file(&data_path("ivanov-lab-32.csv"), LAB_G).expect("lab data reads");
    check_choice("lab", &lab, LAB_G);
}

#[test]
fn leave_one_out_from_each_rows_influence_agrees_with_refits_on_sixty_rows() {
    // Sixty rows, every third with its orientation: every model runs, and most rows' leverage is low
    // enough that their figure comes from the influence rather than a refit.
    let directions = spread_directions(46, 23);
    let rows = rows(&directions, 23, 1.0, |i| i % 3 == 0);
    check_choice("sixty synthetic rows", &dataset(&rows), SYNTHETIC_G);
}

#[test]
fn where_nothing_fits_auto_names_the_closest_model_and_what_to_add() {
    // Five readings, no orientation: diag6 and six-position are each one position short, diag6 the
    // richer; the others need two or more.
    let mut dataset = accelcal::data::read_file(&data_path("huawei-phone-13.csv"), PHONE_G).expect("phone data reads");
    dataset.rows.truncate(5);
    let options = FitOptions { g: PHONE_G, ..FitOptions::default() };
    let error = fit::fit(&dataset, ModelChoice::Auto, &options).unwrap_err();
    println!("{error}");
    assert!(
        matches!(&error, FitError::NothingFits { closest: "diag6", short, .. } if short == " (1 position short)"),
        "{error:?}"
    );
    assert!(error.to_string().ends_with("diag6 needs at least 6 positions; the data has 5: add 1 more"), "{error}");
}
