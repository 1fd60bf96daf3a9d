//! A least-squares problem linearised at one parameter vector: each row's residuals and Jacobian rows,
//! on fixed-size matrices. The solver's interface, the conditioning check and the statistics all read
//! their rows here.

use nalgebra::{Matrix3, SMatrix, Vector3};

use super::nonlinear::Observation;
use super::shape::Shape;

/// The most parameters a least-squares model has (`reference-norm12`).
pub(super) const MAX_PARAMETERS: usize = 12;

/// The model's M, o and every dM/dp_k at one parameter vector.
pub(super) struct Linearised {
    /// Number of matrix parameters.
    n: usize,
    /// M.
    pub matrix: Matrix3<f64>,
    /// o (solver units).
    pub offset: Vector3<f64>,
    /// dM/dp_k for k < n.
    derivatives: [Matrix3<f64>; MAX_PARAMETERS - 3],
}

/// One observation's residuals and Jacobian rows: three for a reference row, one (along the
/// corrected reading) for a norm row; the rows past `count` and the columns past the model's
/// parameters are zero.
pub(super) struct RowsAt {
    pub jacobian: SMatrix<f64, 3, MAX_PARAMETERS>,
    pub residuals: Vector3<f64>,
    pub count: usize,
    /// The direction of the corrected reading M (m - o), for a norm row.
    pub direction: Option<Vector3<f64>>,
}

impl Linearised {
    /// At the parameters `params` (the shape's, then o').
    pub(super) fn new(shape: Shape, params: &[f64]) -> Self {
        let n = shape.len();
        let p = &params[..n];
        let derivatives = std::array::from_fn(|k| if k < n { shape.derivative(p, k) } else { Matrix3::zeros() });
        let offset = Vector3::new(params[n], params[n + 1], params[n + 2]);
        Linearised { n, matrix: shape.matrix(p), offset, derivatives }
    }

    /// The weighted residuals of one observation (a - ref, or |a| - 1) and how many there are.
    pub(super) fn residuals(&self, observation: &Observation) -> (Vector3<f64>, usize) {
        let a = self.matrix * (observation.reading - self.offset);
        match observation.reference {
            Some(reference) => ((a - reference) * observation.weight, 3),
            None => (Vector3::new((a.norm() - 1.0) * observation.weight, 0.0, 0.0), 1),
        }
    }

    /// The weighted residuals and Jacobian rows of one observation.
    pub(super) fn rows(&self, observation: &Observation) -> RowsAt {
        let (residuals, count) = self.residuals(observation);
        let centered = observation.reading - self.offset;
        let mut jacobian = SMatrix::<f64, 3, MAX_PARAMETERS>::zeros();
        let direction = match observation.reference {
            Some(_) => {
                for (k, d) in self.derivatives[..self.n].iter().enumerate() {
                    jacobian.set_column(k, &(d * centered));
                }
                jacobian.fixed_view_mut::<3, 3>(0, self.n).copy_from(&(-self.matrix));
                None
            }
            None => Some(self.norm_row(&mut jacobian, &centered)),
        };
        jacobian *= observation.weight;
        RowsAt { jacobian, residuals, count, direction }
    }

    /// The Jacobian row of a norm residual |a| - 1 into the first row; returns a's direction.
    fn norm_row(&self, jacobian: &mut SMatrix<f64, 3, MAX_PARAMETERS>, centered: &Vector3<f64>) -> Vector3<f64> {
        let a = self.matrix * centered;
        let direction = a / a.norm();
        for (k, d) in self.derivatives[..self.n].iter().enumerate() {
            jacobian[(0, k)] = direction.dot(&(d * centered));
        }
        let offset_row = -(direction.transpose() * self.matrix);
        jacobian.fixed_view_mut::<1, 3>(0, self.n).copy_from(&offset_row);
        direction
    }
}
