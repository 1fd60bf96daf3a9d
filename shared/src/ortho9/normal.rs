//! The 9x9 normal equations of the `ortho9` fit and their guarded Cholesky solve.

// NOTE: the triangular loops index two matrices at once; indices read as the textbook formulas.
#![allow(clippy::needless_range_loop)]

use num_traits::Float;

use super::{residual_and_gradient, Ortho9Error, Params, PARAMETERS};
use crate::linalg::Vec3;

/// A symmetric 9x9 matrix, row-major.
pub(super) type Square<T> = [[T; PARAMETERS]; PARAMETERS];

/// J^T J, J^T r and the cost sum r^2 at one parameter vector.
#[derive(Debug, Clone, Copy)]
pub(super) struct Normal<T> {
    /// J^T J.
    pub jtj: Square<T>,
    /// J^T r.
    pub jtr: Params<T>,
    /// Sum of squared residuals (dimensionless: residuals are in units of g).
    pub cost: T,
}

/// Accumulates the normal equations over the readings; refuses values that are not finite.
pub(super) fn accumulate<T: Float>(readings: &[Vec3<T>], p: &Params<T>) -> Result<Normal<T>, Ortho9Error> {
    let mut normal =
        Normal { jtj: [[T::zero(); PARAMETERS]; PARAMETERS], jtr: [T::zero(); PARAMETERS], cost: T::zero() };
    for &reading in readings {
        let (r, row) = residual_and_gradient(p, reading);
        normal.cost = normal.cost + r * r;
        for i in 0..PARAMETERS {
            normal.jtr[i] = normal.jtr[i] + row[i] * r;
            // NOTE: only the lower triangle is summed; the upper is mirrored once at the end.
            for j in 0..=i {
                normal.jtj[i][j] = normal.jtj[i][j] + row[i] * row[j];
            }
        }
    }
    for i in 0..PARAMETERS {
        for j in 0..i {
            normal.jtj[j][i] = normal.jtj[i][j];
        }
    }
    let finite = normal.cost.is_finite() && normal.jtr.iter().chain(normal.jtj.iter().flatten()).all(|v| v.is_finite());
    finite.then_some(normal).ok_or(Ortho9Error::NotFinite)
}

/// Solves (A + lambda diag(A)) x = b by Cholesky on the diagonally scaled matrix.
///
/// NOTE: scaling to a unit diagonal makes the pivots comparable across parameters of different
/// units (scale factors, cross-axis terms, offsets in g); a pivot below `min_pivot` means the readings
/// hardly determine that parameter, and its index is returned as the error.
pub(super) fn solve_scaled<T: Float>(
    a: &Square<T>,
    b: &Params<T>,
    lambda: T,
    min_pivot: T,
) -> Result<Params<T>, usize> {
    let mut d = [T::zero(); PARAMETERS];
    for (k, dk) in d.iter_mut().enumerate() {
        if a[k][k].is_nan() || a[k][k] <= T::zero() {
            return Err(k);
        }
        *dk = T::one() / a[k][k].sqrt();
    }
    let mut l = [[T::zero(); PARAMETERS]; PARAMETERS];
    for i in 0..PARAMETERS {
        for j in 0..=i {
            let mut sum = a[i][j] * d[i] * d[j];
            if i == j {
                sum = sum + lambda;
            }
            for k in 0..j {
                sum = sum - l[i][k] * l[j][k];
            }
            if i == j {
                if sum.is_nan() || sum <= min_pivot * (T::one() + lambda) {
                    return Err(i);
                }
                l[i][i] = sum.sqrt();
            } else {
                l[i][j] = sum / l[j][j];
            }
        }
    }
    Ok(substitute(&l, b, &d))
}

/// x = D L^-T L^-1 D b: the forward and back substitutions of the scaled system.
fn substitute<T: Float>(l: &Square<T>, b: &Params<T>, d: &Params<T>) -> Params<T> {
    let mut y = [T::zero(); PARAMETERS];
    for i in 0..PARAMETERS {
        let mut sum = b[i] * d[i];
        for k in 0..i {
            sum = sum - l[i][k] * y[k];
        }
        y[i] = sum / l[i][i];
    }
    for i in (0..PARAMETERS).rev() {
        let mut sum = y[i];
        for k in i + 1..PARAMETERS {
            sum = sum - l[k][i] * y[k];
        }
        y[i] = sum / l[i][i];
    }
    let mut x = y;
    for (xi, di) in x.iter_mut().zip(d) {
        *xi = *xi * *di;
    }
    x
}
