//! The 9-parameter orientation-free fit `ortho9`: M = T K with T = [[1, a_yz, a_zy], [0, 1, a_zx],
//! [0, 0, 1]] and K = diag(s_x, s_y, s_z), offset o, minimising sum (|M (m_i - o)| - 1)^2 over
//! readings in g (the published MPU-6050 model of data/README.md).
//!
//! A small Levenberg-Marquardt on the 9x9 normal equations: fixed size, no allocation, generic over
//! f32 (chip) and f64 (host). NOTE: nalgebra's static matrices (Cholesky on `SMatrix`) would solve
//! it in no_std as well; it is written here for flash. The firmware must fit 64 KiB (`cargo xtask
//! dist`) and the Black Pill images leave 228-312 B of it free; measured for thumbv7em at opt-level
//! "s" with fat LTO, the guarded scaled solve of the 9x9 system is 644 B of code written here and
//! 1 044 B on nalgebra 0.34's `SMatrix` Cholesky (+400 B, and 886 B more of memcpy where an image
//! lacks it), so by that measure the chip's fit on nalgebra would not fit the Black Pill. The problem
//! is tiny and well scaled (every parameter of order one near M = I, o = 0), so normal equations with
//! a conditioning guard lose nothing: the guard refuses any problem whose scaled normal matrix has a
//! pivot below [`min_pivot`], which keeps the squared condition number far from the float type's
//! rounding.

mod normal;
#[cfg(test)]
mod tests;

use num_traits::Float;
use serde::{Deserialize, Serialize};

use crate::linalg::{self, Mat3, Vec3};
use crate::real::Real;
use normal::{accumulate, solve_scaled, Normal};

/// Number of parameters: a_yz, a_zy, a_zx, s_x, s_y, s_z, o_x, o_y, o_z (offset in g).
pub const PARAMETERS: usize = 9;
/// The fewest readings that can determine the nine parameters.
pub const MIN_READINGS: usize = PARAMETERS;
/// Iterations after which the fit gives up.
pub const MAX_ITERATIONS: u32 = 100;

/// The nine parameters in [`PARAMETERS`] order.
pub type Params<T> = [T; PARAMETERS];

/// Why the `ortho9` fit could not run.
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ortho9Error {
    /// Fewer than [`MIN_READINGS`] readings (the count found, saturated at 255).
    TooFewReadings(u8),
    /// The readings hardly determine this parameter (index in [`PARAMETERS`] order): add positions
    /// spread over the sphere.
    IllConditioned(u8),
    /// The iterations ran out before the steps became negligible.
    NotConverged,
    /// A reading or an intermediate value is not finite.
    NotFinite,
}

/// A converged `ortho9` fit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ortho9Fit<T> {
    /// The parameters in [`PARAMETERS`] order (scales dimensionless, offset in g).
    pub params: Params<T>,
    /// Sum of squared residuals (|a_i| - 1)^2, dimensionless.
    pub cost: T,
    /// Levenberg-Marquardt iterations taken (each solves the 9x9 system once).
    pub iterations: u32,
}

impl<T: Float> Ortho9Fit<T> {
    /// The correction matrix M = T K.
    pub fn matrix(&self) -> Mat3<T> {
        matrix_of(&self.params)
    }

    /// The offset o, in g.
    pub fn offset(&self) -> Vec3<T> {
        [self.params[6], self.params[7], self.params[8]]
    }
}

/// The parameters of M = I, o = 0: where the fit starts for readings in g.
pub fn identity<T: Float>() -> Params<T> {
    let (o, z) = (T::one(), T::zero());
    [z, z, z, o, o, o, z, z, z]
}

/// M = T K for the parameters `p`.
pub fn matrix_of<T: Float>(p: &Params<T>) -> Mat3<T> {
    let z = T::zero();
    [[p[3], p[0] * p[4], p[1] * p[5]], [z, p[4], p[2] * p[5]], [z, z, p[5]]]
}

/// The smallest pivot the scaled normal matrix may have: a hundred times the float's epsilon
/// (f64 2.2e-14, f32 1.2e-5), so the solve keeps at least two digits above rounding.
pub fn min_pivot<T: Float>() -> T {
    T::epsilon() * T::from(100.0).unwrap_or_else(T::one)
}

/// The stopping rule's tolerance: the fit ends at a step of at most this times |parameters| (f64
/// 1.5e-10, f32 3.5e-6), as Ceres' `parameter_tolerance` and scipy's `xtol` do.
///
/// NOTE: the cost cannot see a parameter error below about sqrt(epsilon) (it changes by the error's
/// square); a hundredth of that ends the fit once the steps carry nothing the cost could confirm.
pub fn step_tolerance<T: Real>() -> T {
    T::epsilon().root() * constant(0.01)
}

/// Fits `ortho9` to readings in g, starting from M = I, o = 0.
pub fn fit<T: Real>(readings: &[Vec3<T>]) -> Result<Ortho9Fit<T>, Ortho9Error> {
    fit_from(readings, identity())
}

/// Fits `ortho9` to readings in g from the parameters `start`.
pub fn fit_from<T: Real>(readings: &[Vec3<T>], start: Params<T>) -> Result<Ortho9Fit<T>, Ortho9Error> {
    fit_checked(readings, start, |_| Ok(()))
}

/// J^T J at the fit's start, its lower triangle (entry [i][j] for j <= i, the rest zero), in
/// [`PARAMETERS`] order: what [`fit_checked`] hands its check.
pub type StartNormal<T> = [[T; PARAMETERS]; PARAMETERS];

/// Fits as [`fit_from`] does, once `check` has accepted J^T J at `start`; its error ends the fit.
///
/// NOTE: for a caller with its own conditioning rule (the host's names the parameter and warns of a
/// poor condition number): it reads the normal equations the first step solves anyway, where building
/// them again took a third of the host's whole fit.
pub fn fit_checked<T: Real, E: From<Ortho9Error>>(
    readings: &[Vec3<T>],
    start: Params<T>,
    check: impl FnOnce(&StartNormal<T>) -> Result<(), E>,
) -> Result<Ortho9Fit<T>, E> {
    if readings.len() < MIN_READINGS {
        return Err(Ortho9Error::TooFewReadings(readings.len().min(255) as u8).into());
    }
    // NOTE: built in place, not returned from a constructor: moving the solver copies its two 9x9
    // systems, which on the chip took a sixth of the fit.
    let normals = [Normal::new(), Normal::new()];
    let mut solver = Solver { readings, params: start, normals, current: 0, lambda: T::zero() };
    if !accumulate(readings, &start, &mut solver.normals[0]) {
        return Err(Ortho9Error::NotFinite.into());
    }
    check(&solver.normals[0].jtj)?;
    for iteration in 1..=MAX_ITERATIONS {
        if solver.step()? {
            let cost = cost(readings, &solver.params);
            return Ok(Ortho9Fit { params: solver.params, cost, iterations: iteration });
        }
    }
    Err(Ortho9Error::NotConverged.into())
}

/// Levenberg-Marquardt's state: parameters, their normal equations and the damping.
struct Solver<'a, T> {
    readings: &'a [Vec3<T>],
    params: Params<T>,
    /// The normal equations at `params` (`normals[current]`) and at the step being tried: the two
    /// swap roles when a step is taken, so no 9x9 matrix is ever copied.
    normals: [Normal<T>; 2],
    current: usize,
    /// Damping of the scaled normal matrix; zero (plain Gauss-Newton) until a step fails.
    lambda: T,
}

impl<'a, T: Real> Solver<'a, T> {
    /// One damped step; `Ok(true)` once converged.
    ///
    /// NOTE: the first solve is undamped, so its Cholesky is also the conditioning check: a pivot
    /// below [`min_pivot`] names a parameter the readings hardly determine. A negligible step is taken
    /// unchecked and ends the fit: it costs nothing and leaves the parameters at their rounding floor.
    fn step(&mut self) -> Result<bool, Ortho9Error> {
        let normal = &self.normals[self.current];
        let delta = solve_scaled(&normal.jtj, &normal.jtr, self.lambda, min_pivot())
            .map_err(|k| Ortho9Error::IllConditioned(k as u8))?;
        let trial = core::array::from_fn(|k| self.params[k] + delta[k]);
        if negligible(&delta, &self.params) {
            self.params = trial;
            return Ok(true);
        }
        let (cost, next) = (normal.cost, 1 - self.current);
        let resolution = cost_resolution(cost, self.readings.len());
        if accumulate(self.readings, &trial, &mut self.normals[next]) && self.normals[next].cost <= cost + resolution {
            (self.params, self.current) = (trial, next);
            self.lambda = self.lambda * constant(0.1);
            return Ok(false);
        }
        // NOTE: when no step however short lowers the cost, the cost is at its rounding floor.
        self.lambda = (self.lambda * constant(10.0)).max(constant(1e-3));
        Ok(self.lambda > constant(1e12))
    }
}

/// Whether a step is below the solver's resolution: |delta| <= [`step_tolerance`] |params|.
fn negligible<T: Real>(delta: &Params<T>, params: &Params<T>) -> bool {
    let squared = |v: &Params<T>| v.iter().fold(T::zero(), |sum, x| sum + *x * *x);
    let tolerance = step_tolerance::<T>();
    squared(delta) <= tolerance * tolerance * squared(params)
}

/// How far the cost can move by rounding alone: each residual |a| - 1 carries an absolute error of a
/// few epsilons, so the cost about 2 sqrt(n cost) of them.
///
/// NOTE: near the minimum the last Gauss-Newton step lowers the cost by less than that; judged by
/// the cost it would be refused, and the fit would stop short of the minimum by about sqrt(epsilon).
fn cost_resolution<T: Real>(cost: T, readings: usize) -> T {
    let n = T::from(readings).unwrap_or_else(T::one);
    T::epsilon() * constant(64.0) * (n * cost).root()
}

/// Sum of squared residuals at `p`.
fn cost<T: Real>(readings: &[Vec3<T>], p: &Params<T>) -> T {
    let (matrix, offset) = (matrix_of(p), [p[6], p[7], p[8]]);
    readings.iter().fold(T::zero(), |sum, &m| {
        let a = linalg::mul_vec(&matrix, linalg::sub(m, offset));
        let r = linalg::dot(a, a).root() - T::one();
        sum + r * r
    })
}

/// The residual |M (m - o)| - 1 of one reading and its gradient over the parameters.
fn residual_and_gradient<T: Real>(p: &Params<T>, m: Vec3<T>) -> (T, Params<T>) {
    let (a_yz, a_zy, a_zx, s_x, s_y, s_z) = (p[0], p[1], p[2], p[3], p[4], p[5]);
    let c = linalg::sub(m, [p[6], p[7], p[8]]);
    let a = linalg::mul_vec(&matrix_of(p), c);
    let length = linalg::dot(a, a).root();
    let u = linalg::scale(a, T::one() / length);
    // d|a|/dM_ij = u_i c_j; each parameter's dM/dp picks its entries.
    let column_z = u[0] * a_zy + u[1] * a_zx + u[2];
    let gradient = [
        u[0] * s_y * c[1],
        u[0] * s_z * c[2],
        u[1] * s_z * c[2],
        u[0] * c[0],
        (u[0] * a_yz + u[1]) * c[1],
        column_z * c[2],
        -(u[0] * s_x),
        -((u[0] * a_yz + u[1]) * s_y),
        -(column_z * s_z),
    ];
    (length - T::one(), gradient)
}

/// A literal in the float type.
fn constant<T: Float>(value: f64) -> T {
    T::from(value).unwrap_or_else(T::zero)
}
