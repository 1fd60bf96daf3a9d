//! The least-squares models `reference-norm12`, `ortho9` and `diag6`: observability checks, the
//! normalised solve, and the map back to the file's units with standard errors.

use nalgebra::{DMatrix, DVector, Vector3};

use super::nonlinear::{solve, Observation, Problem, Solution};
use super::normalization::Normalization;
use super::ortho9;
use super::shape::Shape;
use super::{statistics, Fit, FitError, FitOptions, Model, NoiseTest, Parameter};
use crate::data::Dataset;
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
    check_positions(training, model, shape)?;
    let readings: Vec<[f64; 3]> = training.rows.iter().map(|r| r.reading).collect();
    let normalization = Normalization::from_readings(&readings);
    let observations = observations(training, model, &normalization, options.g);
    let mut start = shape.identity();
    start.extend([0.0; 3]);
    let start = DVector::from_vec(start);
    let mut warnings = Vec::new();
    check_conditioning(model, shape, &observations, &start, &mut warnings)?;
    let solution = if ortho9::applies(shape, &observations) {
        ortho9::solve(&observations)?
    } else {
        solve(shape, &observations, start)?
    };
    let std_errors = standard_errors(&solution);
    let parameters = file_parameters(shape, &solution, std_errors.as_ref(), &normalization, options.g);
    let noise_test = statistics::noise_test(training, shape, &solution, &observations, &normalization);
    warnings.extend(noise_test.as_ref().and_then(noise_warning));
    let (matrix, offset) = calibration_of(shape, &parameters);
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
    })
}

/// The rows as the solver sees them: normalised readings, references in g where the model uses them.
pub(super) fn observations(
    training: &Dataset,
    model: Model,
    normalization: &Normalization,
    g: f64,
) -> Vec<Observation> {
    let uses_references = model == Model::ReferenceNorm12;
    let observation = |row: &crate::data::Row| Observation {
        reading: normalization.apply(row.reading),
        reference: row.reference.filter(|_| uses_references).map(|r| Vector3::from(r) / g),
    };
    training.rows.iter().map(observation).collect()
}

/// M and o from the parameters in the file's units.
fn calibration_of(shape: Shape, parameters: &[Parameter]) -> (Mat3<f64>, Vec3<f64>) {
    let values: Vec<f64> = parameters.iter().map(|p| p.value).collect();
    let matrix = shape.matrix(&values[..shape.len()]);
    let offset = [0, 1, 2].map(|k| values[shape.len() + k]);
    ([0, 1, 2].map(|i| [0, 1, 2].map(|j| matrix[(i, j)])), offset)
}

/// The warning for residuals larger than the capture noise explains.
fn noise_warning(test: &NoiseTest) -> Option<String> {
    (!test.passed).then(|| {
        format!(
            "the residuals exceed what the capture noise explains (chi-square {:.1} on {} degrees of freedom, \
             p = {:.1e}): the board moved between captures, or the model is too simple",
            test.chi_square, test.degrees_of_freedom, test.p_value
        )
    })
}

/// Refuses, before fitting, positions that cannot determine the model, naming what to add.
fn check_positions(training: &Dataset, model: Model, shape: Shape) -> Result<(), FitError> {
    if model == Model::ReferenceNorm12 {
        return check_references(training, model, shape);
    }
    let needed = shape.len() + 3;
    if training.rows.len() < needed {
        return Err(FitError::TooFewPositions { model: model.name(), needed, found: training.rows.len() });
    }
    for (axis, letter) in ['x', 'y', 'z'].into_iter().enumerate() {
        for up in [true, false] {
            if !points_along(training, axis, up) {
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

/// Whether some reading points `axis` up (or down) within the spread the fits need.
fn points_along(training: &Dataset, axis: usize, up: bool) -> bool {
    let sign = if up { 1.0 } else { -1.0 };
    training.rows.iter().any(|r| {
        let m = Vector3::from(r.reading);
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

/// Standard errors in the solver's units: s^2 (J^T J)^-1 with s^2 the residual variance.
fn standard_errors(solution: &Solution) -> Option<DVector<f64>> {
    let (residuals, parameters) = solution.jacobian.shape();
    let dof = residuals.checked_sub(parameters).filter(|&d| d > 0)?;
    let variance = solution.cost / dof as f64;
    let normal = solution.jacobian.transpose() * &solution.jacobian;
    let covariance = normal.cholesky()?.inverse() * variance;
    Some(covariance.diagonal().map(f64::sqrt))
}

/// The parameters in the file's units: M = g M' diag(1/r), o = c + r o'.
fn file_parameters(
    shape: Shape,
    solution: &Solution,
    std_errors: Option<&DVector<f64>>,
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
        parameters.push(Parameter {
            name: parameter_name(shape, k),
            value: solution.params[k] * factor + shift,
            std_error: std_errors.map(|e| e[k] * factor),
        });
    }
    parameters
}
