//! The six-position closed form (Georgieva and Hofreither): from the averaged readings with each axis
//! up and down, `m = X a + y` gives X column k = (m(+k) - m(-k)) / 2g, y = mean of the six, and the
//! calibration M = X^-1, o = y.
//!
//! Generic over the float type: the chip runs it in f32, the host checks it in f64 with the same code.

use num_traits::Float;
use serde::{Deserialize, Serialize};

use crate::linalg::{self, Mat3, Vec3};
use crate::orientation::{Position, PositionMap};

/// Why the six-position fit could not run.
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq, Eq)]
pub enum SixPositionError {
    /// No reading for this position.
    Missing(Position),
    /// The readings do not determine X (opposite faces read the same, or values are not finite).
    Degenerate,
}

/// The six-position fit over one averaged reading per position (any unit).
impl<T: Float> PositionMap<Vec3<T>> {
    /// Fits `m = X a + y` and returns the calibration M = X^-1, o = y, with `g` the magnitude of
    /// gravity in the readings' unit (1 for readings in g).
    pub fn fit(&self, g: T) -> Result<SixPositionFit<T>, SixPositionError> {
        // X column k = (m(+k) - m(-k)) / 2g; built as rows of X^T, one per axis.
        let mut columns = [[T::zero(); 3]; 3];
        let mut sum = [T::zero(); 3];
        for (axis, column) in columns.iter_mut().enumerate() {
            let up = self.require(Position::from_axis(axis, true))?;
            let down = self.require(Position::from_axis(axis, false))?;
            *column = linalg::scale(linalg::sub(up, down), T::one() / (g + g));
            sum = linalg::add(sum, linalg::add(up, down));
        }
        let x = linalg::transpose(&columns);
        let six = T::from(6.0).ok_or(SixPositionError::Degenerate)?;
        let offset = linalg::scale(sum, T::one() / six);
        let matrix = linalg::inverse(&x).ok_or(SixPositionError::Degenerate)?;
        if matrix.iter().flatten().chain(&offset).any(|v| !v.is_finite()) {
            return Err(SixPositionError::Degenerate);
        }
        Ok(SixPositionFit { matrix, offset, sensor_matrix: x })
    }

    fn require(&self, position: Position) -> Result<Vec3<T>, SixPositionError> {
        self.get(position).copied().ok_or(SixPositionError::Missing(position))
    }
}

/// The result of the six-position closed form, in the readings' unit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SixPositionFit<T> {
    /// Correction matrix M = X^-1.
    pub matrix: Mat3<T>,
    /// Offset o = y, in the readings' unit.
    pub offset: Vec3<T>,
    /// The sensor's own error matrix X (m = X a + y), before inversion.
    pub sensor_matrix: Mat3<T>,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sensor with scale, cross-axis and offset errors: m = X a + y.
    const X: Mat3<f64> = [[1.021, 0.013, -0.004], [-0.007, 0.985, 0.009], [0.002, -0.011, 1.034]];
    const Y: Vec3<f64> = [0.0276, -0.0057, -0.0783];

    fn readings_of(x: &Mat3<f64>, y: Vec3<f64>, g: f64) -> PositionMap<Vec3<f32>> {
        let mut set = PositionMap::new();
        for position in Position::ALL {
            let a = linalg::scale(position.specific_force_g(), g);
            let m = linalg::add(linalg::mul_vec(x, a), y);
            set.insert(position, m.map(|v| v as f32)).unwrap();
        }
        set
    }

    #[test]
    fn recovers_a_known_error_model_from_noise_free_readings_to_f32_precision() {
        let fit = readings_of(&X, Y, 1.0).fit(1.0f32).unwrap();
        let truth = linalg::inverse(&X).unwrap();
        for (row, truth_row) in fit.matrix.iter().zip(&truth) {
            for (&got, &want) in row.iter().zip(truth_row) {
                assert!((got as f64 - want).abs() < 4.0 * f32::EPSILON as f64, "{got} vs {want}");
            }
        }
        for (&got, &want) in fit.offset.iter().zip(&Y) {
            assert!((got as f64 - want).abs() < 4.0 * f32::EPSILON as f64, "{got} vs {want}");
        }
    }

    #[test]
    fn scales_with_g_so_readings_in_any_unit_give_the_same_matrix() {
        let in_g = readings_of(&X, Y, 1.0).fit(1.0f32).unwrap();
        let in_si = readings_of(&X, linalg::scale(Y, 9.81), 9.81).fit(9.81f32).unwrap();
        assert!(linalg::max_abs_diff(&in_g.matrix, &in_si.matrix) < 1e-5);
        assert!((in_si.offset[2] / 9.81 - in_g.offset[2]).abs() < 1e-6);
    }

    #[test]
    fn names_the_missing_position() {
        let full = readings_of(&X, Y, 1.0);
        for missing in Position::ALL {
            let mut set = PositionMap::new();
            for p in full.present().filter(|p| *p != missing) {
                set.insert(p, *full.get(p).unwrap()).unwrap();
            }
            assert_eq!(set.fit(1.0), Err(SixPositionError::Missing(missing)));
            assert_eq!(set.first_missing(), Some(missing));
        }
    }

    #[test]
    fn a_second_reading_for_a_position_is_refused_and_the_first_kept() {
        let mut set = readings_of(&X, Y, 1.0);
        let first = *set.get(Position::NegY).unwrap();
        assert_eq!(set.insert(Position::NegY, [0.0, -1.0, 0.0]), Err(Position::NegY));
        assert_eq!(set.get(Position::NegY), Some(&first));
    }

    #[test]
    fn opposite_faces_reading_alike_is_degenerate() {
        let mut set = readings_of(&X, Y, 1.0);
        set.replace(Position::NegZ, *set.get(Position::PosZ).unwrap());
        assert_eq!(set.fit(1.0), Err(SixPositionError::Degenerate));
    }
}
