//! What leaving one row out does to a least-squares solution, without refitting: the removal of
//! residual rows J_i, r_i moves the parameters by
//!
//! delta_i = (J^T J - J_i^T J_i)^-1 J_i^T r_i = A^-1 J_i^T (I - H_ii)^-1 r_i,   H_ii = J_i A^-1 J_i^T
//!
//! (A = J^T J; the second form by the push-through identity, so one inverse of A serves every row).
//! It is exact for a linear problem (the classical leave-one-out residual r_i / (1 - h_ii)) and the
//! Gauss-Newton step from the solution for a nonlinear one; H_ii is the row's block of the hat
//! matrix, its leverage. Source of the method: case deletion in Cook and Weisberg, "Residuals and
//! Influence in Regression" (1982), with its one-step approximation for nonlinear least squares.

use nalgebra::DMatrix;

/// The inverse normal matrix of a solution's Jacobian, shared by every row's removal.
pub(super) struct Influence {
    inverse_normal: DMatrix<f64>,
}

/// One row's removal: the parameters' change and the row's leverage.
pub(super) struct Removal {
    /// The change of the parameters (one column per column of the residuals given).
    pub step: DMatrix<f64>,
    /// The largest eigenvalue of the row's hat-matrix block (0 to 1).
    pub leverage: f64,
}

impl Influence {
    /// From the Jacobian of the residuals at the solution (weighted as the fit weighs them); `None`
    /// when the rows do not determine the parameters.
    pub(super) fn new(jacobian: &DMatrix<f64>) -> Option<Self> {
        let normal = jacobian.transpose() * jacobian;
        Some(Influence { inverse_normal: normal.cholesky()?.inverse() })
    }

    /// The parameters' change when the residual rows `jacobian_rows` (k x p) with residuals
    /// `residuals` (k x c: c problems sharing one design) leave the fit; `None` when the other rows no
    /// longer determine the parameters.
    pub(super) fn removal(&self, jacobian_rows: &DMatrix<f64>, residuals: &DMatrix<f64>) -> Option<Removal> {
        let spread = &self.inverse_normal * jacobian_rows.transpose();
        let hat = jacobian_rows * &spread;
        let leverage = hat.clone().symmetric_eigen().eigenvalues.max();
        let remaining = DMatrix::identity(hat.nrows(), hat.ncols()) - hat;
        let scaled = remaining.lu().solve(residuals)?;
        let step = spread * scaled;
        step.iter().all(|v| v.is_finite()).then_some(Removal { step, leverage })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::DVector;

    /// A straight line through noisy points: the step from the formula equals the refit without the row.
    #[test]
    fn a_rows_removal_step_equals_the_refit_without_it_for_a_linear_problem() {
        let x = [0.0, 1.0, 2.0, 3.0, 4.5, 6.0];
        let y = [0.1, 0.9, 2.3, 2.8, 4.9, 5.7];
        let design = DMatrix::from_fn(x.len(), 2, |i, j| if j == 0 { 1.0 } else { x[i] });
        let solve = |rows: &[usize]| {
            let d = design.select_rows(rows);
            let v = DVector::from_iterator(rows.len(), rows.iter().map(|&i| y[i]));
            (d.transpose() * &d).cholesky().unwrap().solve(&(d.transpose() * v))
        };
        let all: Vec<usize> = (0..x.len()).collect();
        let fitted = solve(&all);
        // NOTE: residuals r = y - D b have the Jacobian -D.
        let jacobian = -&design;
        let residuals = DMatrix::from_fn(x.len(), 1, |i, _| y[i] - (design.row(i) * &fitted)[0]);
        let influence = Influence::new(&jacobian).unwrap();
        for i in 0..x.len() {
            let removal =
                influence.removal(&jacobian.rows(i, 1).into_owned(), &residuals.rows(i, 1).into_owned()).unwrap();
            let without: Vec<usize> = all.iter().copied().filter(|&k| k != i).collect();
            let refit = solve(&without);
            assert!((&fitted + removal.step.column(0) - &refit).amax() < 1e-12, "row {i}");
            assert!(removal.leverage > 0.0 && removal.leverage < 1.0);
        }
    }
}
