//! A least-squares problem linearised at one parameter vector: each row's residuals and Jacobian rows,
//! on fixed-size matrices. The solver's interface, the conditioning check and the statistics all read
//! their rows here.

use nalgebra::{Const, Dyn, Matrix3, OMatrix, SMatrix, Vector3};

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
    /// dM/dp_k for k < n, by its nonzero entries: each at most three (row, column, value), the
    /// unused ones of value zero.
    derivatives: [[(usize, usize, f64); 3]; MAX_PARAMETERS - 3],
}

/// One observation's weighted residuals: three for a reference row, one (along the corrected
/// reading) for a norm row; the residuals past `count` are zero.
pub(super) struct RowsAt {
    pub residuals: Vector3<f64>,
    pub count: usize,
    /// The direction of the corrected reading M (m - o), for a norm row.
    pub direction: Option<Vector3<f64>>,
}

/// One observation's weighted Jacobian rows over `P` parameters, transposed (a column per residual,
/// `count` of them; the rest are zero).
pub(super) type RowsTransposed<const P: usize> = SMatrix<f64, P, 3>;

/// Every observation's Jacobian rows stacked, transposed (a column per residual, over the model's
/// `P` parameters): J^T J and its kin then come from one matrix product each.
pub(super) struct Stacked<const P: usize> {
    transposed: OMatrix<f64, Const<P>, Dyn>,
    /// Columns filled so far.
    filled: usize,
}

impl<const P: usize> Stacked<P> {
    /// Room for the residuals of `observations`: three for a reference row, one for a norm row.
    pub(super) fn for_observations(observations: &[Observation]) -> Self {
        let residuals = observations.iter().map(|o| if o.reference.is_some() { 3 } else { 1 }).sum();
        Stacked { transposed: OMatrix::zeros_generic(Const::<P>, Dyn(residuals)), filled: 0 }
    }

    /// Appends one observation's rows, each multiplied by `scale` (the identity for J itself; V_i
    /// for V J).
    #[inline(always)]
    pub(super) fn push(&mut self, (rows, count): (&RowsTransposed<P>, usize), scale: &Matrix3<f64>) {
        if count == 1 {
            let column = rows.column(0) * scale[(0, 0)];
            self.transposed.fixed_view_mut::<P, 1>(0, self.filled).copy_from(&column);
        } else {
            let columns = rows * scale.transpose();
            self.transposed.fixed_view_mut::<P, 3>(0, self.filled).copy_from(&columns);
        }
        self.filled += count;
    }

    /// (this)^T `other`: J^T J with `other` this, J^T V J with this V J.
    pub(super) fn tr_mul(&self, other: &Stacked<P>) -> SMatrix<f64, P, P> {
        let mut product = SMatrix::<f64, P, P>::zeros();
        for (mine, theirs) in self.transposed.column_iter().zip(other.transposed.column_iter()) {
            product.syger(1.0, &mine, &theirs, 1.0);
        }
        product.fill_upper_triangle_with_lower_triangle();
        product
    }
}

impl Linearised {
    /// At the parameters `params` (the shape's, then o').
    pub(super) fn new(shape: Shape, params: &[f64]) -> Self {
        let n = shape.len();
        let p = &params[..n];
        let derivatives =
            std::array::from_fn(|k| if k < n { nonzero(&shape.derivative(p, k)) } else { [(0, 0, 0.0); 3] });
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

    /// The weighted residuals and Jacobian rows (transposed, over `P` >= the model's parameters) of
    /// one observation.
    // NOTE: inlined into each pass, so the rows are built where they are stacked rather than
    // returned and copied: the statistics pass went from 3.8 to 2.9 us on the bench's problems.
    #[inline(always)]
    pub(super) fn rows<const P: usize>(&self, observation: &Observation) -> (RowsTransposed<P>, RowsAt) {
        let (centered, weight) = (observation.reading - self.offset, observation.weight);
        let a = self.matrix * centered;
        let mut rows = RowsTransposed::<P>::zeros();
        let at = match observation.reference {
            Some(reference) => {
                for (k, entries) in self.derivatives[..self.n].iter().enumerate() {
                    for &(i, j, value) in entries {
                        rows[(k, i)] += value * centered[j] * weight;
                    }
                }
                rows.fixed_view_mut::<3, 3>(self.n, 0).copy_from(&(-self.matrix.transpose() * weight));
                RowsAt { residuals: (a - reference) * weight, count: 3, direction: None }
            }
            None => {
                let length = a.norm();
                let direction = a / length;
                for (k, entries) in self.derivatives[..self.n].iter().enumerate() {
                    rows[(k, 0)] =
                        entries.iter().map(|&(i, j, value)| direction[i] * value * centered[j]).sum::<f64>() * weight;
                }
                rows.fixed_view_mut::<3, 1>(self.n, 0).copy_from(&(-self.matrix.tr_mul(&direction) * weight));
                RowsAt {
                    residuals: Vector3::new((length - 1.0) * weight, 0.0, 0.0),
                    count: 1,
                    direction: Some(direction),
                }
            }
        };
        (rows, at)
    }
}

/// The nonzero entries of a derivative dM/dp_k (at most three in every model), padded with zeros.
fn nonzero(derivative: &Matrix3<f64>) -> [(usize, usize, f64); 3] {
    let mut entries = [(0, 0, 0.0); 3];
    let found = (0..9).map(|e| (e / 3, e % 3)).filter(|&(i, j)| derivative[(i, j)] != 0.0);
    for (slot, (i, j)) in entries.iter_mut().zip(found) {
        *slot = (i, j, derivative[(i, j)]);
    }
    entries
}
