//! The least-squares models `reference-norm12`, `ortho9` and `diag6`: observability checks, the
//! normalised solve, and the map back to the file's units with standard errors.

use nalgebra::{DVector, Matrix3, SVector, Vector3};

use super::covariance::{self, Accumulated, Square};
use super::linearised::Observation;
use super::linearised::MAX_PARAMETERS;
use super::nonlinear::{solve, Solution};
use super::normalization::Normalization;
use super::observability::{check_conditioning, check_normal, check_positions};
use super::ortho9;
use super::prediction::{self, Prediction};
use super::shape::{parameter_name, Shape};
use super::{statistics, uncertainty, verdict, Fit, FitError, FitOptions, Model, NoiseTest, Parameter};
use crate::data::{Dataset, Row};
use shared::linalg::{Mat3, Vec3};

/// Fits one model to the training rows: the closed forms in `linear`, the rest by least squares.
pub(super) fn fit_model(training: &Dataset, model: Model, options: &FitOptions) -> Result<Fit, FitError> {
    match model {
        Model::SixPosition => super::linear::six_position(training, options),
        Model::Linear12 => super::linear::linear12(training, options),
        Model::ReferenceNorm12 | Model::Ortho9 | Model::Diag6 => least_squares(training, model, options),
    }
}

/// The shape of M in a least-squares model.
pub(super) fn shape_of(model: Model) -> Shape {
    match model {
        Model::Diag6 => Shape::Diagonal,
        Model::Ortho9 => Shape::TriangularTimesDiagonal,
        _ => Shape::Full,
    }
}

/// Fits one of the least-squares models to the training rows.
pub(super) fn least_squares(training: &Dataset, model: Model, options: &FitOptions) -> Result<Fit, FitError> {
    let solved = solved(training, model, options)?;
    Ok(match solved.shape {
        Shape::Diagonal => with_statistics::<6>(training, model, options, solved),
        Shape::TriangularTimesDiagonal => with_statistics::<9>(training, model, options, solved),
        Shape::Full => with_statistics::<12>(training, model, options, solved),
    })
}

/// The fit in the file's units with its standard errors, noise test and prediction; `P` the model's
/// parameters, so that its statistics are on fixed-size matrices.
fn with_statistics<const P: usize>(training: &Dataset, model: Model, options: &FitOptions, solved: Solved) -> Fit {
    let Solved { shape, normalization, observations, solution, mut warnings } = solved;
    let sums = covariance::accumulate::<P>(training, shape, &solution, &observations, &normalization);
    let (scatter, noise, inflation, reported) = errors(&sums, solution.cost);
    let errors = [scatter.as_ref().map(|e| e.as_slice()), noise.as_ref().map(|e| e.as_slice())];
    let parameters = file_parameters(shape, &solution, errors, inflation, &normalization, options.g);
    let prediction = reported.map(|c| predicted(shape, &parameters, &normalization, &c, options.g));
    let noise_test = statistics::noise_test(sums.own, sums.residuals, P);
    let (matrix, offset) = calibration_of(shape, &parameters);
    let (m, o) = (Matrix3::from(matrix).transpose(), Vector3::from(offset));
    let degrees_of_freedom = sums.residuals.saturating_sub(P);
    warnings.extend(fit_warnings(training, &observations, degrees_of_freedom, &m, &o, noise_test.as_ref(), options.g));
    Fit {
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
    }
}

/// A least-squares model solved in the solver's units, with what the solve needs to be read.
pub(super) struct Solved {
    pub shape: Shape,
    pub normalization: Normalization,
    pub observations: Vec<Observation>,
    pub solution: Solution,
    /// The condition number's warning, where it is poor.
    pub warnings: Vec<String>,
}

/// Checks that the training rows determine the model, and solves it.
pub(super) fn solved(training: &Dataset, model: Model, options: &FitOptions) -> Result<Solved, FitError> {
    let shape = shape_of(model);
    let normalization = Normalization::of_dataset(training);
    check_positions(training, model, shape, &normalization)?;
    let observations = observations(training, model, &normalization, options.g);
    let start: Vec<f64> = shape.identity().into_iter().chain([0.0; 3]).collect();
    let mut warnings = Vec::new();
    let solution = if ortho9::applies(shape, &observations) {
        ortho9::solve(&observations, |normal| check_normal(model, shape, normal, &mut warnings))?
    } else {
        check_conditioning(model, shape, &observations, &start, &mut warnings)?;
        solve(shape, &observations, DVector::from_vec(start))?
    };
    Ok(Solved { shape, normalization, observations, solution, warnings })
}

/// The prediction at fresh orientations from the covariance in the solver's units.
fn predicted<const P: usize>(
    shape: Shape,
    parameters: &[Parameter],
    normalization: &Normalization,
    covariance: &Square<P>,
    g: f64,
) -> Prediction {
    let n = shape.len();
    let factor =
        |k: usize| if k < n { shape.unit_factor(k, g, &normalization.radii) } else { normalization.radii[k - n] };
    let file = Square::<P>::from_fn(|i, j| factor(i) * covariance[(i, j)] * factor(j));
    let values = SVector::<f64, P>::from_fn(|k, _| parameters[k].value);
    prediction::least_squares(shape, values.as_slice(), &file, g)
}

/// What the noise test's failure points to, and too little redundancy or too short captures.
fn fit_warnings(
    training: &Dataset,
    observations: &[Observation],
    degrees_of_freedom: usize,
    matrix: &Matrix3<f64>,
    offset: &Vector3<f64>,
    noise_test: Option<&NoiseTest>,
    g: f64,
) -> Vec<String> {
    let failed = noise_test.filter(|t| !t.passed);
    let warning =
        failed.map(|t| verdict::noise_warning(&used_references(training, observations), matrix, offset, g, t));
    let mut warnings: Vec<String> = warning.into_iter().collect();
    warnings.extend(uncertainty::redundancy_warnings(training, degrees_of_freedom));
    warnings
}

/// The training rows with only the references the model used: the others say nothing of this fit's
/// placement.
fn used_references(training: &Dataset, observations: &[Observation]) -> Dataset {
    let rows = observations.iter().zip(&training.rows);
    Dataset { rows: rows.map(|(o, r)| Row { reference: o.reference.and(r.reference), ..r.clone() }).collect() }
}

/// Scatter- and noise-based standard errors, the noise's inflation, the reported covariance.
type Errors<const P: usize> = (Option<SVector<f64, P>>, Option<SVector<f64, P>>, f64, Option<Square<P>>);

/// The scatter- and noise-based standard errors in the solver's units, the noise's inflation, and the
/// covariance behind the reported errors (the noise's, inflated, or the scatter's).
fn errors<const P: usize>(sums: &Accumulated<P>, cost: f64) -> Errors<P> {
    let degrees_of_freedom = sums.residuals.saturating_sub(P);
    let (scatter, noise) = covariance::covariances(sums, cost);
    let inflation = noise.map_or(1.0, |(_, chi_square)| uncertainty::inflation(chi_square, degrees_of_freedom));
    let noise = noise.map(|(c, _)| c);
    let reported = noise.map(|c| c * inflation.powi(2)).or(scatter);
    let diagonal = |c: Option<Square<P>>| c.map(|c| c.diagonal().map(|v| v.max(0.0).sqrt()));
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
    let mut values = [0.0; MAX_PARAMETERS];
    for (value, parameter) in values.iter_mut().zip(parameters) {
        *value = parameter.value;
    }
    let matrix = shape.matrix(&values[..shape.len()]);
    let offset = [0, 1, 2].map(|k| values[shape.len() + k]);
    ([0, 1, 2].map(|i| [0, 1, 2].map(|j| matrix[(i, j)])), offset)
}

/// The parameters in the file's units: M = g M' diag(1/r), o = c + r o'; `errors` the scatter- and
/// noise-based standard errors in the solver's units, with the noise's inflation.
fn file_parameters(
    shape: Shape,
    solution: &Solution,
    errors: [Option<&[f64]>; 2],
    inflation: f64,
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
