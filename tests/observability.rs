//! Positions that cannot determine a model are refused before fitting, each with the message the
//! docs/guide.md promises: the numbers (needed, found, how many to add), the axis and direction missing,
//! the parameter the Jacobian cannot see; and a poorly conditioned fit is fitted with a warning.

use accelcal::fit::Model;
use accelcal::fit::{self, FitError, FitOptions, ModelChoice};
use accelcal_tests::data_path;
use accelcal_tests::problem::{self, SyntheticRow, SAMPLE_STD_COUNTS, SYNTHETIC_G};
use nalgebra::Vector3;

fn options() -> FitOptions {
    FitOptions { g: SYNTHETIC_G, ..FitOptions::default() }
}

fn refusal(rows: &[SyntheticRow], model: Model) -> FitError {
    match fit::fit(&problem::dataset(rows), ModelChoice::Only(model), &options()) {
        Ok(fit) => panic!("{} fitted what it should refuse: {:?}", model.name(), fit.parameters),
        Err(error) => error,
    }
}

/// Faces, corners and ten random directions, every fourth row with its orientation.
fn spread_rows() -> Vec<SyntheticRow> {
    problem::rows(&problem::spread_directions(10, 21), 22, 1.0, |i| i % 4 == 0)
}

#[test]
fn too_few_positions_are_refused_with_how_many_are_needed_and_how_many_to_add() {
    let rows = spread_rows();
    assert_eq!(
        refusal(&rows[..8], Model::Ortho9).to_string(),
        "ortho9 needs at least 9 positions; the data has 8: add 1 more"
    );
    assert_eq!(
        refusal(&rows[..3], Model::Diag6).to_string(),
        "diag6 needs at least 6 positions; the data has 3: add 3 more"
    );
    // reference-norm12: rows 1 and 5 carry references (3 residuals each), the other five one each:
    // 11 residuals for 12 parameters; an eighth position makes 12.
    assert_eq!(
        refusal(&rows[..7], Model::ReferenceNorm12).to_string(),
        "reference-norm12 needs at least 8 positions; the data has 7: add 1 more"
    );
    assert!(fit::fit(&problem::dataset(&rows[..8]), ModelChoice::Only(Model::ReferenceNorm12), &options()).is_ok());
}

#[test]
fn a_missing_axis_direction_is_refused_naming_the_axis_and_the_way_to_turn_it() {
    for model in [Model::Ortho9, Model::Diag6] {
        for axis in 0..3 {
            for sign in [1.0, -1.0] {
                // Leave out every position within 84 degrees of this axis direction.
                let rows: Vec<SyntheticRow> = spread_rows().into_iter().filter(|r| sign * r.up[axis] < 0.1).collect();
                let letter = ['x', 'y', 'z'][axis];
                let (way, turn) = if sign > 0.0 { ("up", '+') } else { ("down", '-') };
                let message = refusal(&rows, model).to_string();
                println!("{} rows: {message}", rows.len());
                assert!(message.starts_with(&format!("{} cannot be determined: ", model.name())), "{message}");
                assert!(message.contains(&format!("no position has the {letter} axis pointing {way} ")), "{message}");
                assert!(message.ends_with(&format!("add one with {turn}{letter} up")), "{message}");
            }
        }
    }
}

#[test]
fn too_few_references_are_refused_with_how_many_are_needed_and_found() {
    let rows = spread_rows();
    let with_references = |count: usize| -> Vec<SyntheticRow> {
        let mut rows = rows.clone();
        let mut kept = 0;
        for row in &mut rows {
            if row.reference.is_some() {
                kept += 1;
                if kept > count {
                    row.reference = None;
                }
            }
        }
        rows
    };
    // Two references along the same direction count as one.
    let mut parallel = with_references(1);
    parallel.push(parallel[0].clone());
    for (rows, found) in [(with_references(0), 0), (with_references(1), 1), (parallel, 1)] {
        assert_eq!(
            refusal(&rows, Model::ReferenceNorm12).to_string(),
            format!(
                "reference-norm12 needs at least 2 rows with a known orientation (ref_x,ref_y,ref_z); the file has {found}"
            )
        );
    }
    assert_eq!(
        refusal(&with_references(3), Model::Linear12).to_string(),
        "linear12 needs at least 4 rows with a known orientation (ref_x,ref_y,ref_z); the file has 3"
    );
}

#[test]
fn references_in_one_plane_are_refused_naming_the_axis_out_of_it() {
    for (axis, letter) in ['x', 'y', 'z'].into_iter().enumerate() {
        // Every reference at right angles to this axis: the faces of the other two axes and the
        // diagonals between them.
        let directions: Vec<Vector3<f64>> = problem::spread_directions(40, 23)
            .into_iter()
            .filter(|d| d[axis].abs() < 1e-12 || (d[(axis + 1) % 3].abs() > 0.3 && d[(axis + 2) % 3].abs() > 0.3))
            .map(|mut d| {
                d[axis] = 0.0;
                d.normalize()
            })
            .collect();
        let rows = problem::rows(&directions, 24, 1.0, |_| true);
        assert_eq!(
            refusal(&rows, Model::Linear12).to_string(),
            format!(
                "the known orientations do not determine linear12: they lie in one plane; \
                 add a position with the {letter} axis pointing up or down"
            )
        );
    }
}

/// Readings in one plane: the x and y axes turn round a circle, z reads the same 200 counts on every
/// row (an integer, so that its mean is exact); the rows at 0 and 90 degrees know their orientation.
fn flat_rows() -> Vec<SyntheticRow> {
    (0..12)
        .map(|i| {
            let angle = (30.0 * i as f64).to_radians();
            let up = Vector3::new(angle.cos(), angle.sin(), 0.0);
            SyntheticRow {
                up,
                reading: Vector3::new(400.0 + 16000.0 * up[0], -90.0 + 16500.0 * up[1], 200.0),
                reference: (i == 0 || i == 3).then_some(up * SYNTHETIC_G),
                stated_std: Vector3::from(SAMPLE_STD_COUNTS),
            }
        })
        .collect()
}

#[test]
fn a_parameter_the_jacobian_cannot_see_is_refused_by_name() {
    // Nothing ever moves the z reading: the z column of M (M13, M23, M33) multiplies zero on every row.
    let error = refusal(&flat_rows(), Model::ReferenceNorm12);
    let FitError::Unobservable { model, parameter } = &error else { panic!("{error}") };
    assert_eq!(*model, "reference-norm12");
    assert!(["M13", "M23", "M33"].contains(&parameter.as_str()), "{error}");
    assert_eq!(
        error.to_string(),
        format!(
            "reference-norm12 cannot be determined from these positions: {parameter} is not observable; \
             add positions spread over the sphere"
        )
    );
}

#[test]
fn a_parameter_the_jacobian_barely_sees_is_refused_too() {
    // The z readings differ by thousandths of a count: not exactly flat, but far below what the fit
    // could resolve (condition number beyond 1e7).
    let mut rows = flat_rows();
    for (i, row) in rows.iter_mut().enumerate() {
        row.reading[2] += 1e-3 * [1.0, -1.0, 0.5, 0.0, -0.5, 1.0, 0.3, -0.7, 0.2, 0.9, -0.4, 0.6][i];
    }
    let error = refusal(&rows, Model::ReferenceNorm12);
    assert!(matches!(error, FitError::Unobservable { model: "reference-norm12", .. }), "{error}");
}

#[test]
fn the_published_lab_fit_warns_of_the_condition_number_the_readme_quotes() {
    // docs/measurements.md, "Results on the published data": "The fit warns of a condition number of 1.2e4: the 20
    // training rows never point z down."
    let g = 9.8061;
    let dataset = accelcal::data::read_file(&data_path("ivanov-lab-32.csv"), g).unwrap();
    let options = FitOptions {
        g,
        training_rows: Some((1..=20).collect()),
        reference_rows: Some(vec![1, 10]),
        ..FitOptions::default()
    };
    let fit = fit::fit(&dataset, ModelChoice::Only(Model::ReferenceNorm12), &options).unwrap();
    println!("{:?}", fit.warnings);
    let warning = fit.warnings.iter().find(|w| w.contains("condition number")).expect("a condition warning");
    // The weakest direction of the scaled Jacobian is mostly the x offset.
    assert_eq!(
        warning,
        "poor condition number 1.2e4: the positions barely determine o_x; add positions spread over the sphere"
    );
}
