//! The least-squares models `reference-norm12`, `ortho9` and `diag6`: observability checks, the
//! normalised solve, and the map back to the file's units with standard errors.

use nalgebra::{DMatrix, DVector, Matrix3, Vector3};

use super::nonlinear::{solve, Observation, Problem, Solution};
use super::normalization::Normalization;
use super::ortho9;
use super::prediction::{self, Prediction};
use super::shape::Shape;
use super::{statistics, uncertainty, verdict, Fit, FitError, FitOptions, Model, NoiseTest, Parameter};
use crate::data::{Dataset, Row};
use crate::limits::{AXIS_SPREAD, INDEPENDENT_REFERENCES_DEG};
use levenberg_marquardt::LeastSquaresProblem;
use shared::linalg::{Mat3, Vec3};

/// Known orientations `reference-norm12` needs at least [`INDEPENDENT_REFERENCES_DEG`] apart: two fix
/// the rotation that the |a| = g rows cannot see.
const INDEPENDENT_REFERENCES: usize = 2;
/// Below this ratio of smallest to largest singular value the parameters are not observable.
/// NOTE: the ratio comes from eigenvalues of J^T J, whose rounding floor is 1e-16 relative: 1e-7 in
/// singular values stays clear of it.
const UNOBSERVABLE_RATIO: f64 = 1e-7;
/// Below this ratio the condition number is worth a warning.
const POORLY_CONDITIONED_RATIO: f64 = 1e-3;

fn shape_of(model: Model) -> Shape {
    match model {
        Model::Diag6 => Shape::Diagonal,
        Model::Ortho9 => Shape::TriangularTimesDiagonal,
        _ => Shape::Full,
    }
}

/// Fits one of the least-squares models to the training rows.
pub(super) fn least_squares(training: &Dataset, model: Model, options: &FitOptions) -> Result<Fit, FitError> {
    let shape = shape_of(model);
    let normalization = Normalization::of_dataset(training);
    check_positions(training, model, shape, &normalization)?;
    let observations = observations(training, model, &normalization, options.g);
    let start = DVector::from_iterator(shape.len() + 3, shape.identity().into_iter().chain([0.0; 3]));
    let mut warnings = Vec::new();
    check_conditioning(model, shape, &observations, &start, &mut warnings)?;
    let solution = ortho9::solve_or(shape, &observations, || solve(shape, &observations, start))?;
    let (scatter, noise, inflation, reported) = errors(training, shape, &solution, &observations, &normalization);
    let errors = ([scatter.as_ref(), noise.as_ref()], inflation);
    let parameters = file_parameters(shape, &solution, errors, &normalization, options.g);
    let prediction = reported.map(|c| predicted(shape, &parameters, &normalization, &c, options.g));
    let noise_test = statistics::noise_test(training, shape, &solution, &observations, &normalization);
    let (matrix, offset) = calibration_of(shape, &parameters);
    let calibration = (Matrix3::from(matrix).transpose(), Vector3::from(offset));
    warnings.extend(fit_warnings(training, &observations, &solution, calibration, (noise_test.as_ref(), options.g)));
    Ok(Fit {
        model,
        matrix,
        offset,
        cost: solution.cost,
        iterations: solution.evaluations,
        parameters,
        lines_used: training.rows.iter().map(|r| r.line).collect(),
        noise_test,
        warnings,
        selection: None,
        prediction,
    })
}

/// The prediction at fresh orientations from the covariance in the solver's units.
fn predicted(
    shape: Shape,
    parameters: &[Parameter],
    normalization: &Normalization,
    covariance: &DMatrix<f64>,
    g: f64,
) -> Prediction {
    let n = shape.len();
    let factors = DVector::from_fn(n + 3, |k, _| {
        if k < n {
            shape.unit_factor(k, g, &normalization.radii)
        } else {
            normalization.radii[k - n]
        }
    });
    let file = DMatrix::from_diagonal(&factors) * covariance * DMatrix::from_diagonal(&factors);
    let values: Vec<f64> = parameters.iter().map(|p| p.value).collect();
    prediction::least_squares(shape, &values, &file, g)
}

/// What the noise test's failure points to, and too little redundancy or too short captures.
fn fit_warnings(
    training: &Dataset,
    observations: &[Observation],
    solution: &Solution,
    (matrix, offset): (Matrix3<f64>, Vector3<f64>),
    (noise_test, g): (Option<&NoiseTest>, f64),
) -> Vec<String> {
    // NOTE: with only the references the model used: the others say nothing of this fit's placement.
    let rows = observations.iter().zip(&training.rows);
    let used =
        Dataset { rows: rows.map(|(o, r)| Row { reference: o.reference.and(r.reference), ..r.clone() }).collect() };
    let failed = noise_test.filter(|t| !t.passed);
    let mut warnings: Vec<String> =
        failed.map(|t| verdict::noise_warning(&used, (&matrix, &offset), g, t)).into_iter().collect();
    let degrees_of_freedom = solution.residuals.len().saturating_sub(solution.params.len());
    warnings.extend(uncertainty::redundancy_warnings(training, degrees_of_freedom));
    warnings
}

/// Scatter- and noise-based standard errors, the noise's inflation, the reported covariance.
type Errors = (Option<DVector<f64>>, Option<DVector<f64>>, f64, Option<DMatrix<f64>>);

/// The scatter- and noise-based standard errors in the solver's units, the noise's inflation, and the
/// covariance behind the reported errors (the noise's, inflated, or the scatter's).
fn errors(
    training: &Dataset,
    shape: Shape,
    solution: &Solution,
    observations: &[Observation],
    normalization: &Normalization,
) -> Errors {
    let degrees_of_freedom = solution.residuals.len().saturating_sub(solution.params.len());
    let noise = uncertainty::noise_errors(training, shape, solution, observations, normalization);
    let inflation = noise.as_ref().map_or(1.0, |n| uncertainty::inflation(n.chi_square, degrees_of_freedom));
    let (scatter, noise) = (scatter_covariance(solution), noise.map(|n| n.covariance));
    let reported = noise.as_ref().map(|c| c * inflation.powi(2)).or(scatter.clone());
    let diagonal = |c: Option<DMatrix<f64>>| c.map(|c| uncertainty::diagonal_errors(&c));
    (diagonal(scatter), diagonal(noise), inflation, reported)
}

/// The rows as the solver sees them: normalised readings, references in g where the model uses them,
/// weights from the samples each row averaged.
pub(super) fn observations(
    training: &Dataset,
    model: Model,
    normalization: &Normalization,
    g: f64,
) -> Vec<Observation> {
    let uses_references = model == Model::ReferenceNorm12;
    let weights = uncertainty::row_weights(training);
    let observation = |(row, weight): (&crate::data::Row, f64)| Observation {
        reading: normalization.apply(row.reading),
        reference: row.reference.filter(|_| uses_references).map(|r| Vector3::from(r) / g),
        weight: weight.sqrt(),
    };
    training.rows.iter().zip(weights).map(observation).collect()
}

/// M and o from the parameters in the file's units.
fn calibration_of(shape: Shape, parameters: &[Parameter]) -> (Mat3<f64>, Vec3<f64>) {
    let values: Vec<f64> = parameters.iter().map(|p| p.value).collect();
    let matrix = shape.matrix(&values[..shape.len()]);
    let offset = [0, 1, 2].map(|k| values[shape.len() + k]);
    ([0, 1, 2].map(|i| [0, 1, 2].map(|j| matrix[(i, j)])), offset)
}

/// Refuses, before fitting, positions that cannot determine the model, naming what to add; judged on
/// the normalised readings, so that the file's zero and unit do not matter.
fn check_positions(
    training: &Dataset,
    model: Model,
    shape: Shape,
    normalization: &Normalization,
) -> Result<(), FitError> {
    if model == Model::ReferenceNorm12 {
        return check_references(training, model, shape);
    }
    let needed = shape.len() + 3;
    if training.rows.len() < needed {
        return Err(FitError::TooFewPositions { model: model.name(), needed, found: training.rows.len() });
    }
    for (axis, letter) in ['x', 'y', 'z'].into_iter().enumerate() {
        for up in [true, false] {
            if !points_along(training, normalization, axis, up) {
                return Err(FitError::NoSpread { model: model.name(), axis: letter, up });
            }
        }
    }
    Ok(())
}

/// `reference-norm12` needs two independent known orientations and one residual per parameter.
fn check_references(training: &Dataset, model: Model, shape: Shape) -> Result<(), FitError> {
    let name = model.name();
    let references: Vec<[f64; 3]> = training.rows.iter().filter_map(|r| r.reference).collect();
    let independent =
        references.iter().any(|a| references.iter().any(|b| angle_between(a, b) > INDEPENDENT_REFERENCES_DEG));
    if !independent {
        return Err(FitError::TooFewReferences {
            model: name,
            needed: INDEPENDENT_REFERENCES,
            found: references.len().min(1),
        });
    }
    let residuals = training.rows.len() + 2 * references.len();
    if residuals < shape.len() + 3 {
        let needed = training.rows.len() + shape.len() + 3 - residuals;
        return Err(FitError::TooFewPositions { model: name, needed, found: training.rows.len() });
    }
    Ok(())
}

/// Whether some normalised reading points `axis` up (or down) within the spread the fits need.
fn points_along(training: &Dataset, normalization: &Normalization, axis: usize, up: bool) -> bool {
    let sign = if up { 1.0 } else { -1.0 };
    training.rows.iter().any(|r| {
        let m = normalization.apply(r.reading);
        sign * m[axis] > AXIS_SPREAD * m.norm()
    })
}

fn angle_between(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    shared::orientation::angle_between_deg(*a, *b)
}

/// Refuses parameters the positions cannot determine, from the column-scaled Jacobian at the start;
/// warns when the condition number is poor.
fn check_conditioning(
    model: Model,
    shape: Shape,
    observations: &[Observation],
    start: &DVector<f64>,
    warnings: &mut Vec<String>,
) -> Result<(), FitError> {
    let jacobian = Problem::new(shape, observations, start.clone()).jacobian().ok_or(FitError::Degenerate)?;
    let (ratio, weakest) = conditioning(shape, &jacobian);
    if ratio < UNOBSERVABLE_RATIO {
        return Err(FitError::Unobservable { model: model.name(), parameter: weakest });
    }
    if ratio < POORLY_CONDITIONED_RATIO {
        warnings.push(format!(
            "poor condition number {:.1e}: the positions barely determine {weakest}; add positions spread over the sphere",
            1.0 / ratio
        ));
    }
    Ok(())
}

/// The ratio of smallest to largest singular value of the column-scaled Jacobian, and the parameter
/// the smallest one weighs most.
fn conditioning(shape: Shape, jacobian: &DMatrix<f64>) -> (f64, String) {
    // NOTE: the singular values of the column-scaled Jacobian are the square roots of the
    // eigenvalues of its small normal matrix, which is much cheaper to decompose than J itself.
    let scaled = column_scaled(jacobian);
    let eigen = (scaled.transpose() * &scaled).symmetric_eigen();
    let (largest, smallest) = (eigen.eigenvalues.max().max(0.0).sqrt(), eigen.eigenvalues.min().max(0.0).sqrt());
    let ratio = if largest > 0.0 { smallest / largest } else { 0.0 };
    let (index, _) = eigen.eigenvalues.argmin();
    (ratio, parameter_name(shape, eigen.eigenvectors.column(index).iamax()))
}

fn column_scaled(jacobian: &DMatrix<f64>) -> DMatrix<f64> {
    let mut scaled = jacobian.clone();
    for mut column in scaled.column_iter_mut() {
        let norm = column.norm();
        if norm > 0.0 {
            column /= norm;
        }
    }
    scaled
}

pub(super) fn parameter_name(shape: Shape, index: usize) -> String {
    shape.names().get(index).map_or_else(|| format!("o_{}", ['x', 'y', 'z'][index - shape.len()]), |n| (*n).to_owned())
}

/// Parameter covariance in the solver's units: s^2 (J^T J)^-1 with s^2 the residual variance.
fn scatter_covariance(solution: &Solution) -> Option<DMatrix<f64>> {
    let (residuals, parameters) = solution.jacobian.shape();
    let dof = residuals.checked_sub(parameters).filter(|&d| d > 0)?;
    let variance = solution.cost / dof as f64;
    let normal = solution.jacobian.transpose() * &solution.jacobian;
    Some(normal.cholesky()?.inverse() * variance)
}

/// The parameters in the file's units: M = g M' diag(1/r), o = c + r o'; `errors` the scatter- and
/// noise-based standard errors in the solver's units, with the noise's inflation.
fn file_parameters(
    shape: Shape,
    solution: &Solution,
    (errors, inflation): ([Option<&DVector<f64>>; 2], f64),
    normalization: &Normalization,
    g: f64,
) -> Vec<Parameter> {
    let n = shape.len();
    let mut parameters = Vec::with_capacity(n + 3);
    for k in 0..n + 3 {
        let (factor, shift) = if k < n {
            (shape.unit_factor(k, g, &normalization.radii), 0.0)
        } else {
            (normalization.radii[k - n], normalization.center[k - n])
        };
        let errors = errors.map(|e| e.map(|e| e[k] * factor));
        let value = solution.params[k] * factor + shift;
        parameters.push(Parameter::new(parameter_name(shape, k), value, errors, inflation));
    }
    parameters
}
