//! What a fit's uncertainty means for the user: the | |a| - g | error and the tilt error it predicts
//! at a fresh orientation, from the parameter covariance; and the angles between the sensor's axes
//! that the matrix implies (Ivanov et al.'s model (4): 90 degrees each for perfectly orthogonal axes).

use nalgebra::{DMatrix, Matrix3, Matrix4, Vector3, Vector4};
use serde::Serialize;
use shared::linalg::Mat3;

use super::shape::Shape;

/// Fresh orientations over which the prediction is averaged (a Fibonacci sphere).
const FRESH_ORIENTATIONS: usize = 200;

/// The errors a calibration's own uncertainty predicts at a fresh orientation, RMS over the sphere.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Prediction {
    /// RMS of | |a| - g |, in mg of the output unit's g.
    pub norm_error_mg: f64,
    /// RMS angle between the corrected and the true specific force, in degrees.
    pub tilt_error_deg: f64,
}

/// Evenly spread unit vectors.
fn fresh_orientations() -> impl Iterator<Item = Vector3<f64>> {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..FRESH_ORIENTATIONS).map(move |i| {
        let z = 1.0 - 2.0 * (i as f64 + 0.5) / FRESH_ORIENTATIONS as f64;
        let radius = (1.0 - z * z).sqrt();
        let angle = golden * i as f64;
        Vector3::new(radius * angle.cos(), radius * angle.sin(), z)
    })
}

/// The prediction from `covariance_of(u)`, the covariance of the corrected reading a (output units)
/// at true specific force g u.
pub fn predict(g: f64, covariance_of: impl Fn(&Vector3<f64>) -> Matrix3<f64>) -> Prediction {
    let (mut norm, mut tilt) = (0.0, 0.0);
    for u in fresh_orientations() {
        let covariance = covariance_of(&u);
        norm += (u.transpose() * covariance * u)[0];
        tilt += covariance.trace() - (u.transpose() * covariance * u)[0];
    }
    let n = FRESH_ORIENTATIONS as f64;
    Prediction { norm_error_mg: (norm / n).sqrt() / g * 1000.0, tilt_error_deg: ((tilt / n).sqrt() / g).to_degrees() }
}

/// The prediction of a least-squares model from its parameters and their covariance in the file's
/// units: da = sum_k dM/dp_k (m - o) dp_k - M do.
pub(super) fn least_squares(shape: Shape, parameters: &[f64], covariance: &DMatrix<f64>, g: f64) -> Prediction {
    let n = shape.len();
    let matrix = shape.matrix(&parameters[..n]);
    let sensor = matrix.try_inverse().unwrap_or_else(Matrix3::zeros);
    predict(g, |u| {
        let centered = sensor * (u * g);
        let mut jacobian = DMatrix::zeros(3, n + 3);
        for k in 0..n {
            jacobian.column_mut(k).copy_from(&(shape.derivative(&parameters[..n], k) * centered));
        }
        jacobian.view_mut((0, n), (3, 3)).copy_from(&(-matrix));
        let a = &jacobian * covariance * jacobian.transpose();
        Matrix3::from_fn(|i, j| a[(i, j)])
    })
}

/// The prediction of a linear model (a = M (m - y), m = X a + y) from the per-reading-axis
/// covariances of (X row, y): each axis c of m errs by (dX a + dy)_c, variance [a 1] C_c [a 1]^T,
/// and a by -M times that.
pub(super) fn linear(matrix: &Mat3<f64>, covariances: &[Matrix4<f64>; 3], g: f64) -> Prediction {
    let m = Matrix3::from_fn(|i, j| matrix[i][j]);
    predict(g, |u| {
        let a = u * g;
        let extended = Vector4::new(a[0], a[1], a[2], 1.0);
        let reading = Vector3::from_fn(|c, _| (extended.transpose() * covariances[c] * extended)[0]);
        m * Matrix3::from_diagonal(&reading) * m.transpose()
    })
}

/// The three angles between the sensor's axes, in degrees (x-y, x-z, y-z): the angles between the
/// rows of the sensor matrix M^-1, each row the direction an axis senses.
pub fn axis_angles_deg(matrix: &Mat3<f64>) -> Option<[f64; 3]> {
    let sensor = Matrix3::from_fn(|i, j| matrix[i][j]).try_inverse()?;
    let row = |i: usize| sensor.row(i).transpose();
    let angle = |i: usize, j: usize| row(i).angle(&row(j)).to_degrees();
    Some([angle(0, 1), angle(0, 2), angle(1, 2)])
}
