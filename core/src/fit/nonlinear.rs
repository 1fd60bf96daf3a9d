//! The nonlinear models (`reference-norm12`, `ortho9`, `diag6`), solved with the levenberg-marquardt
//! crate on a problem normalised from the data, so that any unit works without tuning.
//!
//! Normalisation: an axis-aligned ellipsoid fitted to the readings gives a centre c and radii r; the
//! solver sees m' = (m - c) / r and specific force in g, where the answer is near M' = I, o' = 0 and
//! every parameter is of order one. The result is mapped back: M = g M' diag(1/r), o = c + r o'.

use levenberg_marquardt::{LeastSquaresProblem, LevenbergMarquardt};
use nalgebra::{DMatrix, DVector, Dyn, Owned};

use super::linearised::{Linearised, Observation, RowsAt, RowsTransposed, MAX_PARAMETERS};
use super::shape::Shape;
use super::FitError;

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
        let at = Linearised::new(self.shape, self.params.as_slice());
        let mut residuals = Vec::with_capacity(self.residual_count());
        for observation in self.observations {
            let (values, count) = at.residuals(observation);
            residuals.extend_from_slice(&values.as_slice()[..count]);
        }
        Some(DVector::from_vec(residuals))
    }

    fn jacobian(&self) -> Option<DMatrix<f64>> {
        let at = Linearised::new(self.shape, self.params.as_slice());
        let columns = self.params.len();
        let mut jacobian = DMatrix::zeros(self.residual_count(), columns);
        let mut row = 0;
        let mut rows = RowsTransposed::<{ MAX_PARAMETERS }>::zeros();
        for observation in self.observations {
            let RowsAt { count, .. } = at.rows(observation, &mut rows);
            jacobian.view_mut((row, 0), (count, columns)).copy_from(&rows.view((0, 0), (columns, count)).transpose());
            row += count;
        }
        Some(jacobian)
    }
}

/// A converged solution; its statistics are linearised at `params` (fit/linearised.rs).
#[derive(Debug, Clone)]
pub(super) struct Solution {
    /// Parameters in the solver's units.
    pub params: DVector<f64>,
    /// Sum of squared residuals (dimensionless).
    pub cost: f64,
    /// Residual evaluations the solver made.
    pub evaluations: usize,
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
    })
}

#[cfg(test)]
mod tests {
    use nalgebra::Vector3;

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
