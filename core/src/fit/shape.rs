//! The shape of M in each least-squares model, as a function of its parameters.

use nalgebra::Matrix3;

/// How M depends on the model's matrix parameters.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Shape {
    /// `diag6`: M = diag(s_x, s_y, s_z).
    Diagonal,
    /// `ortho9`: M = T K with T = [[1, a_yz, a_zy], [0, 1, a_zx], [0, 0, 1]], K = diag(s_x, s_y, s_z)
    /// (the published MPU-6050 model of data/README.md).
    TriangularTimesDiagonal,
    /// `reference-norm12`: every entry of M free, M11 ... M33 row-major.
    Full,
}

impl Shape {
    /// Names of the matrix parameters, in parameter order.
    pub(super) fn names(self) -> &'static [&'static str] {
        match self {
            Shape::Diagonal => &["s_x", "s_y", "s_z"],
            Shape::TriangularTimesDiagonal => &["a_yz", "a_zy", "a_zx", "s_x", "s_y", "s_z"],
            Shape::Full => &["M11", "M12", "M13", "M21", "M22", "M23", "M31", "M32", "M33"],
        }
    }

    /// Number of matrix parameters.
    pub(super) fn len(self) -> usize {
        self.names().len()
    }

    /// The parameters that make M the identity.
    pub(super) fn identity(self) -> Vec<f64> {
        match self {
            Shape::Diagonal => vec![1.0; 3],
            Shape::TriangularTimesDiagonal => vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            Shape::Full => Matrix3::<f64>::identity().transpose().iter().copied().collect(),
        }
    }

    /// M for the matrix parameters `p`.
    pub(super) fn matrix(self, p: &[f64]) -> Matrix3<f64> {
        match self {
            Shape::Diagonal => Matrix3::from_diagonal(&[p[0], p[1], p[2]].into()),
            Shape::TriangularTimesDiagonal => {
                let (a_yz, a_zy, a_zx, s_x, s_y, s_z) = (p[0], p[1], p[2], p[3], p[4], p[5]);
                Matrix3::new(s_x, a_yz * s_y, a_zy * s_z, 0.0, s_y, a_zx * s_z, 0.0, 0.0, s_z)
            }
            Shape::Full => Matrix3::from_row_slice(&p[..9]),
        }
    }

    /// dM / dp_k as a matrix, for the tests that check [`Shape::derivative_entries`].
    #[cfg(test)]
    pub(super) fn derivative(self, p: &[f64], k: usize) -> Matrix3<f64> {
        let mut d = Matrix3::zeros();
        for (i, j, value) in self.derivative_entries(p, k) {
            d[(i, j)] += value;
        }
        d
    }

    /// dM / dp_k by its entries that can be nonzero, each (row, column, value): at most three in
    /// every model, padded with zeros at (0, 0).
    pub(super) fn derivative_entries(self, p: &[f64], k: usize) -> [(usize, usize, f64); 3] {
        let pad = (0, 0, 0.0);
        match self {
            Shape::Diagonal => [(k, k, 1.0), pad, pad],
            Shape::Full => [(k / 3, k % 3, 1.0), pad, pad],
            Shape::TriangularTimesDiagonal => match k {
                0 => [(0, 1, p[4]), pad, pad],
                1 => [(0, 2, p[5]), pad, pad],
                2 => [(1, 2, p[5]), pad, pad],
                3 => [(0, 0, 1.0), pad, pad],
                4 => [(0, 1, p[0]), (1, 1, 1.0), pad],
                _ => [(0, 2, p[1]), (1, 2, p[2]), (2, 2, 1.0)],
            },
        }
    }

    /// The factor that takes matrix parameter `k` from the normalised fit (m' = (m - c) / r, unit g)
    /// to the file's units, where M = g M' diag(1 / r): scale and entry parameters of column j carry
    /// g / r_j, the dimensionless cross-axis terms of `ortho9` carry nothing.
    pub(super) fn unit_factor(self, k: usize, g: f64, radii: &[f64; 3]) -> f64 {
        let column = match self {
            Shape::Diagonal => k,
            Shape::TriangularTimesDiagonal if k < 3 => return 1.0,
            Shape::TriangularTimesDiagonal => k - 3,
            Shape::Full => k % 3,
        };
        g / radii[column]
    }
}

/// The name of parameter `index` of the model of `shape`: the shape's matrix parameters, then o.
pub(super) fn parameter_name(shape: Shape, index: usize) -> &'static str {
    shape.names().get(index).copied().unwrap_or_else(|| ["o_x", "o_y", "o_z"][index - shape.len()])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derivatives_match_finite_differences() {
        let cases = [
            (Shape::Diagonal, vec![1.01, 0.98, 1.03]),
            (Shape::TriangularTimesDiagonal, vec![3.6e-4, -7.3e-3, 4.6e-4, 1.0006, 1.003, 0.9834]),
            (Shape::Full, vec![1.0, 0.01, -0.02, 0.003, 0.99, 0.004, -0.01, 0.02, 1.02]),
        ];
        for (shape, p) in cases {
            for k in 0..shape.len() {
                let step = 1e-6;
                let mut plus = p.clone();
                plus[k] += step;
                let mut minus = p.clone();
                minus[k] -= step;
                let numeric = (shape.matrix(&plus) - shape.matrix(&minus)) / (2.0 * step);
                assert!((numeric - shape.derivative(&p, k)).amax() < 1e-9, "{shape:?} parameter {k}");
            }
        }
    }

    #[test]
    fn identity_parameters_give_the_identity() {
        for shape in [Shape::Diagonal, Shape::TriangularTimesDiagonal, Shape::Full] {
            assert_eq!(shape.matrix(&shape.identity()), Matrix3::identity());
        }
    }
}
