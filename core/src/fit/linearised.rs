//! A least-squares problem linearised at one parameter vector: each row's residuals and Jacobian rows,
//! on fixed-size matrices. The solver's interface, the conditioning check and the statistics all read
//! their rows here.

use nalgebra::{Const, Matrix3, SMatrix, Storage, Vector, Vector3};

use super::shape::Shape;

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
    /// dM/dp_k for k < n, by the entries that can be nonzero ([`Shape::derivative_entries`]).
    derivatives: [[(usize, usize, f64); 3]; MAX_PARAMETERS - 3],
}

/// One observation's weighted residuals: three for a reference row, one (along the corrected
/// reading) for a norm row; the residuals past `count` are zero.
pub(super) struct RowsAt {
    pub residuals: Vector3<f64>,
    pub count: usize,
    /// For a norm row, M^T d with d the direction of the corrected reading M (m - o): the
    /// residual's sensitivity to the reading, which its variance reads.
    pub along: Option<Vector3<f64>>,
}

/// One observation's weighted Jacobian rows over `P` parameters, transposed (a column per residual,
/// `count` of them; the rest are zero).
pub(super) type RowsTransposed<const P: usize> = SMatrix<f64, P, 3>;

/// Sum over the rows added of x y^T, P x P, kept in its lower triangle: J^T J with x = y = a
/// Jacobian row, J^T V J with x the row of V J (and the normalisation's 6 x 6 normal matrix).
///
/// NOTE: summed row by row as they are built, not stacked into a P x N matrix first: the stacked
/// matrices' allocations and nalgebra's rank-one updates on dynamic views took a tenth of the whole
/// fit. The sums are the same, in the same order.
pub(super) struct Gram<const P: usize> {
    lower: SMatrix<f64, P, P>,
}

impl<const P: usize> Gram<P> {
    pub(super) fn new() -> Self {
        Gram { lower: SMatrix::zeros() }
    }

    /// Adds one observation's rows (transposed, `count` of them), x each row multiplied by `scale`
    /// (the identity for J itself; V_i for V J) and y the row itself.
    #[inline(always)]
    pub(super) fn push(&mut self, (rows, count): (&RowsTransposed<P>, usize), scale: &Matrix3<f64>) {
        if count == 1 {
            self.add(&(rows.column(0) * scale[(0, 0)]), &rows.column(0));
        } else {
            let scaled = rows * scale.transpose();
            for c in 0..3 {
                self.add(&scaled.column(c), &rows.column(c));
            }
        }
    }

    /// Adds x y^T.
    #[inline(always)]
    pub(super) fn add<X: Storage<f64, Const<P>>, Y: Storage<f64, Const<P>>>(
        &mut self,
        x: &Vector<f64, Const<P>, X>,
        y: &Vector<f64, Const<P>, Y>,
    ) {
        for j in 0..P {
            for i in j..P {
                self.lower[(i, j)] += x[i] * y[j];
            }
        }
    }

    /// The symmetric sum.
    pub(super) fn matrix(mut self) -> SMatrix<f64, P, P> {
        self.lower.fill_upper_triangle_with_lower_triangle();
        self.lower
    }
}

impl Linearised {
    /// At the parameters `params` (the shape's, then o').
    pub(super) fn new(shape: Shape, params: &[f64]) -> Self {
        let n = shape.len();
        let p = &params[..n];
        let derivatives =
            std::array::from_fn(|k| if k < n { shape.derivative_entries(p, k) } else { [(0, 0, 0.0); 3] });
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
    /// one observation; the rows are written into `rows`, whose columns past `count` are left as
    /// they were.
    // NOTE: inlined into each pass and written into the caller's matrix, so the rows are built
    // where they are summed rather than returned and copied (a copy of 216 bytes per row).
    #[inline(always)]
    pub(super) fn rows<const P: usize>(&self, observation: &Observation, rows: &mut RowsTransposed<P>) -> RowsAt {
        let (centered, weight) = (observation.reading - self.offset, observation.weight);
        let a = self.matrix * centered;
        match observation.reference {
            Some(reference) => {
                rows.fill(0.0);
                for (k, entries) in self.derivatives[..self.n].iter().enumerate() {
                    for &(i, j, value) in entries {
                        rows[(k, i)] += value * centered[j] * weight;
                    }
                }
                rows.fixed_view_mut::<3, 3>(self.n, 0).copy_from(&(-self.matrix.transpose() * weight));
                RowsAt { residuals: (a - reference) * weight, count: 3, along: None }
            }
            None => {
                rows.column_mut(0).fill(0.0);
                let length = a.norm();
                let direction = a / length;
                for (k, entries) in self.derivatives[..self.n].iter().enumerate() {
                    rows[(k, 0)] =
                        entries.iter().map(|&(i, j, value)| direction[i] * value * centered[j]).sum::<f64>() * weight;
                }
                let along = self.matrix.tr_mul(&direction);
                rows.fixed_view_mut::<3, 1>(self.n, 0).copy_from(&(-along * weight));
                RowsAt { residuals: Vector3::new((length - 1.0) * weight, 0.0, 0.0), count: 1, along: Some(along) }
            }
        }
    }
}
