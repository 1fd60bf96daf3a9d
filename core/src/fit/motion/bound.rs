//! The Cramer-Rao bound of a design: the inverse of the Fisher information J^T J of the whitened
//! residuals at the truth, for the fit's own information or less of it; and the fit's standard
//! errors, the same computation at the estimate. What it means at a fresh orientation is the
//! project's one prediction (`fit::predict`).

use nalgebra::{DMatrix, Matrix3};

use super::linearise::{linearise, State};
use super::params::{orientation_column, ACCEL, ACCEL_ENTRIES, MODEL, OFFSET, SKEW};
use super::residuals::{Prepared, Usage};
use super::{JointFit, JointModel, MotionData, Orientation};
use crate::fit::prediction::{predict, Prediction, Quadratic};

/// Which information a bound counts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Information {
    /// The rests' mean readings alone, each rest's orientation free: today's still-capture fit.
    Rests,
    /// The rests and their gyro means, each rest's orientation carried to the next by the gyro.
    GyroLinked,
    /// That and each turn's zero velocity change: the joint fit's own.
    Motion,
}

/// The bound of one design.
#[derive(Debug, Clone, PartialEq)]
pub struct Bound {
    /// The accelerometer's covariance at the bound (M's six upper entries, o's three).
    pub accel_covariance: DMatrix<f64>,
    /// What it predicts at a fresh orientation.
    pub prediction: Prediction,
}

impl Information {
    /// The residuals it counts.
    fn usage(self) -> Usage {
        match self {
            Information::Rests => Usage { rest_gyro: false, links: false, velocity: false },
            Information::GyroLinked => Usage { rest_gyro: true, links: true, velocity: false },
            Information::Motion => Usage::ALL,
        }
    }

    /// Whether column `c` is an unknown it can determine: the still fit knows nothing of the gyro
    /// nor of a rest's heading; the rests linked without the motion nothing of the skew (the rate is
    /// zero at both ends of a turn, so a shift in time leaves the turn's rotation as it was).
    fn keeps(self, c: usize, rests: usize) -> bool {
        match self {
            Information::Rests => c < ACCEL || (0..rests).any(|k| (0..2).any(|a| orientation_column(k, a) == Some(c))),
            Information::GyroLinked => c != SKEW,
            Information::Motion => true,
        }
    }
}

/// The Cramer-Rao bound on the accelerometer for `data`'s design with the true `model` and rest
/// `orientations`; `None` when the information leaves an unknown undetermined.
pub fn bound(
    model: &JointModel,
    orientations: &[Orientation],
    data: &MotionData,
    information: Information,
) -> Option<Bound> {
    let state = State { model: super::params::vector_of(model), orientations: orientations.to_vec() };
    let (_, j) = linearise(&state, data, &Prepared::new(data), information.usage());
    let kept: Vec<usize> = (0..j.ncols()).filter(|&c| information.keeps(c, orientations.len())).collect();
    let covariance = inverse_information(&j.select_columns(&kept))?;
    let accel_covariance = covariance.view((0, 0), (ACCEL, ACCEL)).into_owned();
    let prediction = accel_prediction(&model.accel_matrix, &accel_covariance);
    Some(Bound { accel_covariance, prediction })
}

/// (J^T J)^-1, or `None` when singular.
fn inverse_information(j: &DMatrix<f64>) -> Option<DMatrix<f64>> {
    (j.transpose() * j).cholesky().map(|c| c.inverse())
}

/// The fit's summary at its estimate: standard errors, the prediction, chi^2 per degree of freedom.
pub(super) fn summarise(state: &State, data: &MotionData, prepared: &Prepared, iterations: usize) -> Option<JointFit> {
    let (r, j) = linearise(state, data, prepared, Usage::ALL);
    let covariance = inverse_information(&j)?;
    let model = state.joint_model();
    let accel_covariance = covariance.view((0, 0), (ACCEL, ACCEL)).into_owned();
    Some(JointFit {
        model,
        orientations: state.orientations.clone(),
        std_errors: (0..MODEL).map(|p| covariance[(p, p)].sqrt()).collect(),
        prediction: accel_prediction(&model.accel_matrix, &accel_covariance),
        accel_covariance,
        chi2_per_dof: r.norm_squared() / (r.len() - j.ncols()) as f64,
        iterations,
    })
}

/// The prediction at a fresh orientation from the accelerometer's covariance: a = M (m - o) with
/// m - o = M^-1 u, so da = sum_ij dM_ij e_i (M^-1 u)_j - M do, linear in w = (u, 1) (in g).
pub(super) fn accel_prediction(matrix: &Matrix3<f64>, covariance: &DMatrix<f64>) -> Prediction {
    let sensor = matrix.try_inverse().unwrap_or_else(Matrix3::zeros);
    let jacobians: [DMatrix<f64>; 4] = std::array::from_fn(|a| {
        let mut jacobian = DMatrix::zeros(3, ACCEL);
        if a < 3 {
            ACCEL_ENTRIES.iter().enumerate().for_each(|(k, &(i, j))| jacobian[(i, k)] = sensor[(j, a)]);
        } else {
            jacobian.view_mut((0, OFFSET), (3, 3)).copy_from(&(-matrix));
        }
        jacobian
    });
    let terms: Quadratic = std::array::from_fn(|a| {
        std::array::from_fn(|b| {
            let product = &jacobians[a] * covariance * jacobians[b].transpose();
            Matrix3::from_fn(|i, j| product[(i, j)])
        })
    });
    predict(1.0, &terms)
}
