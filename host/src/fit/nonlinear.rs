//! The nonlinear models (`reference-norm12`, `ortho9`, `diag6`), solved with the levenberg-marquardt
//! crate on a problem normalised from the data, so that any unit works without tuning.
//!
//! Normalisation: an axis-aligned ellipsoid fitted to the readings gives a centre c and radii r; the
//! solver sees m' = (m - c) / r and specific force in g, where the answer is near M' = I, o' = 0 and
//! every parameter is of order one. The result is mapped back: M = g M' diag(1/r), o = c + r o'.

use levenberg_marquardt::{LeastSquaresProblem, LevenbergMarquardt};
use nalgebra::{DMatrix, DVector, Dyn, Matrix3, Owned, Vector3};

use super::shape::Shape;
use super::FitError;

/// One averaged reading as the solver sees it.
#[derive(Debug, Clone, Copy)]
pub(super) struct Observation {
    /// Normalised reading m' = (m - c) / r.
    pub reading: Vector3<f64>,
    /// Known specific force in g, for a reference row; `None` for a row where only |a| = g is known.
    pub reference: Option<Vector3<f64>>,
    /// Factor on this row's residuals: the square root of its weight (1 for rows weighed alike).
    pub weight: f64,
}

/// The least-squares problem handed to the solver. Parameters: the shape's matrix parameters, then o'.
#[derive(Debug, Clone)]
pub(super) struct Problem<'a> {
    shape: Shape,
    observations: &'a [Observation],
    params: DVector<f64>,
}

impl<'a> Problem<'a> {
    pub(super) fn new(shape: Shape, observations: &'a [Observation], params: DVector<f64>) -> Self {
        Problem { shape, observations, params }
    }

    fn split(&self) -> (Matrix3<f64>, Vector3<f64>) {
        let n = self.shape.len();
        let matrix = self.shape.matrix(&self.params.as_slice()[..n]);
        (matrix, Vector3::new(self.params[n], self.params[n + 1], self.params[n + 2]))
    }

    /// Number of residuals: three per reference row, one per norm row.
    pub(super) fn residual_count(&self) -> usize {
        self.observations.iter().map(|o| if o.reference.is_some() { 3 } else { 1 }).sum()
    }

    /// The current parameters.
    pub(super) fn values(&self) -> &DVector<f64> {
        &self.params
    }
}

impl LeastSquaresProblem<f64, Dyn, Dyn> for Problem<'_> {
    type ResidualStorage = Owned<f64, Dyn>;
    type JacobianStorage = Owned<f64, Dyn, Dyn>;
    type ParameterStorage = Owned<f64, Dyn>;

    fn set_params(&mut self, x: &DVector<f64>) {
        self.params.copy_from(x);
    }

    fn params(&self) -> DVector<f64> {
        self.params.clone()
    }

    fn residuals(&self) -> Option<DVector<f64>> {
        let (matrix, offset) = self.split();
        let mut residuals = Vec::with_capacity(self.residual_count());
        for observation in self.observations {
            let a = matrix * (observation.reading - offset);
            match observation.reference {
                Some(reference) => residuals.extend((a - reference).iter().map(|r| r * observation.weight)),
                None => residuals.push((a.norm() - 1.0) * observation.weight),
            }
        }
        Some(DVector::from_vec(residuals))
    }

    fn jacobian(&self) -> Option<DMatrix<f64>> {
        let (matrix, offset) = self.split();
        let n = self.shape.len();
        let p = &self.params.as_slice()[..n];
        let derivatives: Vec<Matrix3<f64>> = (0..n).map(|k| self.shape.derivative(p, k)).collect();
        let mut jacobian = DMatrix::zeros(self.residual_count(), n + 3);
        let mut row = 0;
        for observation in self.observations {
            let centered = observation.reading - offset;
            let used = match observation.reference {
                Some(_) => reference_rows(&mut jacobian, row, &derivatives, &matrix, &centered),
                None => norm_row(&mut jacobian, row, &derivatives, &matrix, &centered),
            };
            jacobian.rows_mut(row, used).scale_mut(observation.weight);
            row += used;
        }
        Some(jacobian)
    }
}

/// The three Jacobian rows of a reference residual a - ref at `row`; returns 3.
fn reference_rows(
    jacobian: &mut DMatrix<f64>,
    row: usize,
    derivatives: &[Matrix3<f64>],
    matrix: &Matrix3<f64>,
    centered: &Vector3<f64>,
) -> usize {
    let n = derivatives.len();
    for (k, d) in derivatives.iter().enumerate() {
        jacobian.view_mut((row, k), (3, 1)).copy_from(&(d * centered));
    }
    jacobian.view_mut((row, n), (3, 3)).copy_from(&(-matrix));
    3
}

/// The Jacobian row of a norm residual |a| - 1 at `row`; returns 1.
fn norm_row(
    jacobian: &mut DMatrix<f64>,
    row: usize,
    derivatives: &[Matrix3<f64>],
    matrix: &Matrix3<f64>,
    centered: &Vector3<f64>,
) -> usize {
    let n = derivatives.len();
    let a = matrix * centered;
    let direction = a / a.norm();
    for (k, d) in derivatives.iter().enumerate() {
        jacobian[(row, k)] = direction.dot(&(d * centered));
    }
    let offset_row = -(direction.transpose() * matrix);
    jacobian.view_mut((row, n), (1, 3)).copy_from(&offset_row);
    1
}

/// A converged solution with what its statistics need.
#[derive(Debug, Clone)]
pub(super) struct Solution {
    /// Parameters in the solver's units.
    pub params: DVector<f64>,
    /// Sum of squared residuals (dimensionless).
    pub cost: f64,
    /// Residual evaluations the solver made.
    pub evaluations: usize,
    /// Residuals at the solution.
    pub residuals: DVector<f64>,
    /// Jacobian at the solution.
    pub jacobian: DMatrix<f64>,
}

/// Minimises the problem from `start`; refuses a run that did not converge.
pub(super) fn solve(shape: Shape, observations: &[Observation], start: DVector<f64>) -> Result<Solution, FitError> {
    let problem = Problem::new(shape, observations, start);
    // NOTE: relative tolerances of 1e-12 on cost, step and gradient: the minimum to twelve digits,
    // the same tolerances the scipy comparison gives least_squares.
    let (problem, report) =
        LevenbergMarquardt::new().with_ftol(1e-12).with_xtol(1e-12).with_gtol(1e-12).minimize(problem);
    if !report.termination.was_successful() {
        return Err(FitError::NotConverged { reason: format!("{:?}", report.termination) });
    }
    let residuals = problem.residuals().ok_or(FitError::Degenerate)?;
    let jacobian = problem.jacobian().ok_or(FitError::Degenerate)?;
    if !residuals.iter().chain(jacobian.iter()).all(|v| v.is_finite()) {
        return Err(FitError::Degenerate);
    }
    Ok(Solution {
        params: problem.values().clone(),
        cost: residuals.norm_squared(),
        evaluations: report.number_of_evaluations,
        residuals,
        jacobian,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_jacobian_matches_finite_differences_for_norm_and_reference_rows() {
        let observations = [
            Observation { reading: Vector3::new(0.9, 0.2, 0.1), reference: None, weight: 1.0 },
            Observation {
                reading: Vector3::new(-0.1, 1.05, -0.2),
                reference: Some(Vector3::new(0.0, 1.0, 0.0)),
                weight: 1.0,
            },
            Observation { reading: Vector3::new(0.3, -0.4, -0.8), reference: None, weight: 1.0 },
        ];
        for shape in [Shape::Diagonal, Shape::TriangularTimesDiagonal, Shape::Full] {
            let mut params = shape.identity();
            for (k, value) in params.iter_mut().enumerate() {
                *value += 0.01 * (k as f64 + 1.0).sin();
            }
            params.extend([0.02, -0.03, 0.05]);
            let problem = Problem::new(shape, &observations, DVector::from_vec(params.clone()));
            let analytic = problem.jacobian().unwrap();
            for k in 0..params.len() {
                let step = 1e-7;
                let shifted = |delta: f64| {
                    let mut p = params.clone();
                    p[k] += delta;
                    Problem::new(shape, &observations, DVector::from_vec(p)).residuals().unwrap()
                };
                let numeric = (shifted(step) - shifted(-step)) / (2.0 * step);
                assert!((numeric - analytic.column(k)).amax() < 1e-7, "{shape:?} parameter {k}");
            }
        }
    }
}
