//! Small fixed-size vector and matrix helpers, generic over `f32` (chip) and `f64` (host checks).
//!
//! Matrices are row-major `[[T; 3]; 3]`, the layout used on the wire and in JSON.

use num_traits::Float;

/// A 3-vector.
pub type Vec3<T> = [T; 3];
/// A row-major 3x3 matrix.
pub type Mat3<T> = [[T; 3]; 3];

/// The 3x3 identity matrix.
pub fn identity<T: Float>() -> Mat3<T> {
    let (o, z) = (T::one(), T::zero());
    [[o, z, z], [z, o, z], [z, z, o]]
}

/// Dot product.
pub fn dot<T: Float>(a: Vec3<T>, b: Vec3<T>) -> T {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Cross product a x b.
pub fn cross<T: Float>(a: Vec3<T>, b: Vec3<T>) -> Vec3<T> {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// Euclidean norm.
pub fn norm<T: Float>(a: Vec3<T>) -> T {
    dot(a, a).sqrt()
}

/// Component-wise a - b.
pub fn sub<T: Float>(a: Vec3<T>, b: Vec3<T>) -> Vec3<T> {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// Component-wise a + b.
pub fn add<T: Float>(a: Vec3<T>, b: Vec3<T>) -> Vec3<T> {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// Transpose.
pub fn transpose<T: Float>(m: &Mat3<T>) -> Mat3<T> {
    [[m[0][0], m[1][0], m[2][0]], [m[0][1], m[1][1], m[2][1]], [m[0][2], m[1][2], m[2][2]]]
}

/// Vector times scalar.
pub fn scale<T: Float>(a: Vec3<T>, s: T) -> Vec3<T> {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// Matrix times vector.
pub fn mul_vec<T: Float>(m: &Mat3<T>, v: Vec3<T>) -> Vec3<T> {
    [dot(m[0], v), dot(m[1], v), dot(m[2], v)]
}

/// Matrix product a b.
pub fn mul_mat<T: Float>(a: &Mat3<T>, b: &Mat3<T>) -> Mat3<T> {
    let column = |j: usize| [b[0][j], b[1][j], b[2][j]];
    let mut out = [[T::zero(); 3]; 3];
    for (i, row) in out.iter_mut().enumerate() {
        for (j, cell) in row.iter_mut().enumerate() {
            *cell = dot(a[i], column(j));
        }
    }
    out
}

/// Determinant.
pub fn determinant<T: Float>(m: &Mat3<T>) -> T {
    dot(m[0], cross(m[1], m[2]))
}

/// Inverse by the adjugate; `None` when the matrix is singular or not finite.
///
/// NOTE: for the well-conditioned near-identity matrices of accelerometer calibration the adjugate is
/// as accurate as an LU decomposition and needs no pivoting logic.
pub fn inverse<T: Float>(m: &Mat3<T>) -> Option<Mat3<T>> {
    let det = determinant(m);
    if !det.is_finite() || det == T::zero() {
        return None;
    }
    // Columns of the inverse are the cross products of the rows, divided by the determinant.
    let c0 = cross(m[1], m[2]);
    let c1 = cross(m[2], m[0]);
    let c2 = cross(m[0], m[1]);
    let inv = T::one() / det;
    Some([
        [c0[0] * inv, c1[0] * inv, c2[0] * inv],
        [c0[1] * inv, c1[1] * inv, c2[1] * inv],
        [c0[2] * inv, c1[2] * inv, c2[2] * inv],
    ])
}

/// Largest absolute entry of a - b, for comparisons in tests and checks.
pub fn max_abs_diff<T: Float>(a: &Mat3<T>, b: &Mat3<T>) -> T {
    let mut worst = T::zero();
    for (ra, rb) in a.iter().zip(b) {
        for (&x, &y) in ra.iter().zip(rb) {
            worst = worst.max((x - y).abs());
        }
    }
    worst
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inverse_times_matrix_is_identity_to_f64_precision() {
        let m = [[1.02, 0.003, -0.01], [0.0, 0.97, 0.004], [0.02, -0.001, 1.05]];
        let inv = inverse(&m).unwrap();
        assert!(max_abs_diff(&mul_mat(&m, &inv), &identity()) < 1e-15);
    }

    #[test]
    fn singular_matrix_has_no_inverse() {
        let m: Mat3<f32> = [[1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0, 0.0, 1.0]];
        assert_eq!(inverse(&m), None);
    }
}
