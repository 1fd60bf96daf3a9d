//! The 9x9 normal equations of the `ortho9` fit and their guarded Cholesky solve.

// NOTE: the triangular loops index two matrices at once; indices read as the textbook formulas.
#![allow(clippy::needless_range_loop)]

use num_traits::Float;

use super::{residual_and_gradient, Params, PARAMETERS};
use crate::linalg::Vec3;
use crate::real::Real;

/// A symmetric 9x9 matrix, row-major; the solve reads only its lower triangle.
pub(super) type Square<T> = [[T; PARAMETERS]; PARAMETERS];

/// J^T J (lower triangle), J^T r and the cost sum r^2 at one parameter vector.
#[derive(Debug, Clone)]
pub(super) struct Normal<T> {
    /// J^T J, its lower triangle (j <= i).
    pub jtj: Square<T>,
    /// J^T r.
    pub jtr: Params<T>,
    /// Sum of squared residuals (dimensionless: residuals are in units of g).
    pub cost: T,
}

impl<T: Float> Normal<T> {
    /// All zero.
    pub fn new() -> Self {
        Normal { jtj: [[T::zero(); PARAMETERS]; PARAMETERS], jtr: [T::zero(); PARAMETERS], cost: T::zero() }
    }
}

/// Accumulates the normal equations at `p` over the readings into `normal`; `false` when a value is
/// not finite.
pub(super) fn accumulate<T: Real>(readings: &[Vec3<T>], p: &Params<T>, normal: &mut Normal<T>) -> bool {
    normal.jtj = [[T::zero(); PARAMETERS]; PARAMETERS];
    normal.jtr = [T::zero(); PARAMETERS];
    normal.cost = T::zero();
    for &reading in readings {
        let (r, row) = residual_and_gradient(p, reading);
        normal.cost = normal.cost + r * r;
        for i in 0..PARAMETERS {
            normal.jtr[i] = normal.jtr[i] + row[i] * r;
            for j in 0..=i {
                normal.jtj[i][j] = normal.jtj[i][j] + row[i] * row[j];
            }
        }
    }
    // NOTE: an off-diagonal sum is bounded by its two diagonal ones (Cauchy-Schwarz), so finite
    // diagonals, J^T r and cost mean a finite system.
    let diagonal = (0..PARAMETERS).map(|k| normal.jtj[k][k]);
    normal.cost.is_finite() && normal.jtr.iter().copied().chain(diagonal).all(|v| v.is_finite())
}

/// Solves (A + lambda diag(A)) x = -g by Cholesky on the diagonally scaled matrix (A's lower
/// triangle): the step that the gradient g = J^T r asks for.
///
/// NOTE: scaling to a unit diagonal makes the pivots comparable across parameters of different
/// units (scale factors, cross-axis terms, offsets in g); a pivot below `min_pivot` means the readings
/// hardly determine that parameter, and its index is returned as the error.
pub(super) fn solve_scaled<T: Real>(a: &Square<T>, g: &Params<T>, lambda: T, min_pivot: T) -> Result<Params<T>, usize> {
    let mut d = [T::zero(); PARAMETERS];
    for (k, dk) in d.iter_mut().enumerate() {
        if a[k][k].is_nan() || a[k][k] <= T::zero() {
            return Err(k);
        }
        *dk = T::one() / a[k][k].root();
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
                l[i][i] = sum.root();
            } else {
                l[i][j] = sum / l[j][j];
            }
        }
    }
    Ok(substitute(&l, g, &d))
}

/// x = -D L^-T L^-1 D g: the forward and back substitutions of the scaled system.
fn substitute<T: Float>(l: &Square<T>, g: &Params<T>, d: &Params<T>) -> Params<T> {
    let mut y = [T::zero(); PARAMETERS];
    for i in 0..PARAMETERS {
        let mut sum = -(g[i] * d[i]);
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
