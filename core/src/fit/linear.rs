//! The linear models: `linear12` (least squares of m = X a + y over rows of known orientation) and the
//! `six-position` closed form, which is the same estimate on exactly the six faces.

use nalgebra::{DMatrix, Matrix3, Matrix4, SymmetricEigen, Vector3};
use shared::linalg::{self, Mat3, Vec3};
use shared::{Position, PositionMap, SixPositionError};

use super::faces::{face_force, rows_at_faces};
use super::fitted::full_parameters;
use super::prediction;
use super::{uncertainty, Fit, FitError, FitOptions, Model};
use crate::data::Dataset;

/// Known-orientation rows needed to determine 12 parameters (each row gives three equations, but the
/// four columns of [a 1] must be independent).
pub(super) const MIN_REFERENCES: usize = 4;

/// A reading paired with its known specific force.
#[derive(Debug, Clone, Copy)]
pub(super) struct Pair {
    /// Index of the row in the data set.
    pub row: usize,
    line: usize,
    pub reading: Vec3<f64>,
    pub reference: Vec3<f64>,
    /// Samples averaged into the reading, where the file says.
    count: Option<u32>,
}

/// Linear least squares of m = X a + y over every row with a known orientation.
pub(super) fn linear12(dataset: &Dataset, options: &FitOptions) -> Result<Fit, FitError> {
    let pairs = reference_pairs(dataset);
    if pairs.len() < MIN_REFERENCES {
        let model = Model::Linear12.name();
        return Err(FitError::TooFewReferences { model, needed: MIN_REFERENCES, found: pairs.len() });
    }
    let per_sample = uncertainty::pooled_sample_variance(dataset);
    let solution = LinearSolution::solve(&pairs, Model::Linear12, per_sample)?;
    let matrix = linalg::inverse(&solution.sensor_matrix).ok_or(FitError::Degenerate)?;
    let offset = solution.offset;
    Ok(solution.into_fit(Model::Linear12, matrix, offset, &pairs, dataset, options.g))
}

/// Every row with a known orientation, in row order.
pub(super) fn reference_pairs(dataset: &Dataset) -> Vec<Pair> {
    let pair = |(row, r): (usize, &crate::data::Row)| {
        r.reference.map(|reference| Pair { row, line: r.line, reading: r.reading, reference, count: r.count })
    };
    dataset.rows.iter().enumerate().filter_map(pair).collect()
}

/// Each pair's weight: its sample count relative to the mean where `per_sample` noise is known and
/// the model is `linear12` (the six-position closed form weighs its six readings alike).
pub(super) fn pair_weights(pairs: &[Pair], model: Model, per_sample: Option<Vector3<f64>>) -> Vec<f64> {
    let counts: Option<Vec<f64>> = pairs.iter().map(|p| p.count.map(f64::from)).collect();
    match (counts, per_sample, model) {
        (Some(counts), Some(_), Model::Linear12) => uncertainty::relative_weights(&counts),
        _ => vec![1.0; pairs.len()],
    }
}

/// The six-position closed form of `shared` (in f64), with standard errors from the equivalent
/// least-squares problem.
pub(super) fn six_position(dataset: &Dataset, options: &FitOptions) -> Result<Fit, FitError> {
    let first_row_at = rows_at_faces(dataset, options.face_tolerance_deg)?;
    let mut readings = PositionMap::<Vec3<f64>>::new();
    let mut pairs: Vec<Pair> = Vec::with_capacity(6);
    for (position, row) in Position::ALL.into_iter().zip(first_row_at) {
        if let Some(row) = row {
            let (line, reading, count) = (dataset.rows[row].line, dataset.rows[row].reading, dataset.rows[row].count);
            readings.replace(position, reading);
            pairs.push(Pair { row, line, reading, reference: face_force(position, options.g), count });
        }
    }
    let closed_form = readings.fit(options.g).map_err(|error| match error {
        SixPositionError::Missing(position) => {
            FitError::MissingPosition { position, tolerance_deg: options.face_tolerance_deg }
        }
        SixPositionError::Degenerate => FitError::Degenerate,
    })?;
    pairs.sort_by_key(|p| p.row);
    let solution = LinearSolution::solve(&pairs, Model::SixPosition, uncertainty::pooled_sample_variance(dataset))?;
    Ok(solution.into_fit(Model::SixPosition, closed_form.matrix, closed_form.offset, &pairs, dataset, options.g))
}

/// Least-squares solution of m = X a + y with the statistics for standard errors.
struct LinearSolution {
    /// X, the sensor's matrix.
    sensor_matrix: Mat3<f64>,
    /// y, the offset in the file's unit.
    offset: Vec3<f64>,
    /// Per reading axis, the covariance of (X row, y) from the residual scatter (`None`: no redundancy).
    scatter: Option<[Matrix4<f64>; 3]>,
    /// Per reading axis, the covariance of (X row, y) from the measured noise, where the file has it.
    noise: Option<[Matrix4<f64>; 3]>,
    /// Residual degrees of freedom per reading axis, and the noise-based errors' factor.
    degrees_of_freedom: usize,
    inflation: f64,
}

impl LinearSolution {
    /// Weighted as [`pair_weights`] says.
    fn solve(pairs: &[Pair], model: Model, per_sample: Option<Vector3<f64>>) -> Result<Self, FitError> {
        check_spread(pairs, model)?;
        let n = pairs.len();
        let counts: Option<Vec<f64>> = pairs.iter().map(|p| p.count.map(f64::from)).collect();
        let weights = pair_weights(pairs, model, per_sample);
        let root = |i: usize| weights[i].sqrt();
        let design = DMatrix::from_fn(n, 4, |i, j| root(i) * if j < 3 { pairs[i].reference[j] } else { 1.0 });
        let readings = DMatrix::from_fn(n, 3, |i, j| root(i) * pairs[i].reading[j]);
        let solution = design.clone().svd(true, true).solve(&readings, 1e-12).map_err(|_| FitError::Degenerate)?;
        let normal: Matrix4<f64> = (design.transpose() * &design).fixed_view::<4, 4>(0, 0).into_owned();
        let inverse_normal = normal.try_inverse().ok_or(FitError::Degenerate)?;
        let residuals = readings - &design * &solution;
        let scatter = (n > MIN_REFERENCES).then(|| {
            [0, 1, 2].map(|j| inverse_normal * (residuals.column(j).norm_squared() / (n - MIN_REFERENCES) as f64))
        });
        let degrees_of_freedom = n.saturating_sub(MIN_REFERENCES);
        let factors = counts.map(|c| c.iter().zip(&weights).map(|(n, w)| w / n).collect());
        let noise = per_sample.zip(factors);
        let (noise, inflation) = uncertainty::linear_noise_errors(&design, &inverse_normal, &residuals, noise);
        Ok(LinearSolution {
            sensor_matrix: [0, 1, 2].map(|row| [0, 1, 2].map(|col| solution[(col, row)])),
            offset: [0, 1, 2].map(|row| solution[(3, row)]),
            scatter,
            noise,
            degrees_of_freedom,
            inflation,
        })
    }

    /// Standard errors of M = X^-1 (propagated: dM = -M dX M) and of o = y, from per-axis
    /// covariances of (X row, y).
    fn std_errors(covariances: Option<[Matrix4<f64>; 3]>, matrix: &Mat3<f64>) -> Option<(Mat3<f64>, Vec3<f64>)> {
        let covariances = covariances?;
        let m = Matrix3::from_fn(|i, j| matrix[i][j]);
        let matrix_errors = [0, 1, 2].map(|a| {
            [0, 1, 2].map(|b| {
                let column: Vector3<f64> = m.column(b).into_owned();
                let variance = |c: usize| {
                    let shape: Matrix3<f64> = covariances[c].fixed_view::<3, 3>(0, 0).into_owned();
                    m[(a, c)].powi(2) * (column.transpose() * shape * column)[0]
                };
                (0..3).map(variance).sum::<f64>().sqrt()
            })
        });
        let offset_errors = [0, 1, 2].map(|c| covariances[c][(3, 3)].sqrt());
        Some((matrix_errors, offset_errors))
    }

    /// The per-axis covariances behind the reported errors: the noise's (scaled) or the scatter's.
    fn reported(&self) -> Option<[Matrix4<f64>; 3]> {
        self.noise.map(|c| c.map(|m| m * self.inflation.powi(2))).or(self.scatter)
    }

    /// The fit of the calibration a = `matrix` (m - `offset`) made from this solution on `pairs` of
    /// `dataset`.
    fn into_fit(
        self,
        model: Model,
        matrix: Mat3<f64>,
        offset: Vec3<f64>,
        pairs: &[Pair],
        dataset: &Dataset,
        g: f64,
    ) -> Fit {
        let cost = pairs
            .iter()
            .map(|p| {
                let corrected = linalg::mul_vec(&matrix, linalg::sub(p.reading, offset));
                let error = linalg::sub(corrected, p.reference);
                linalg::dot(error, error) / (g * g)
            })
            .sum();
        let (scatter, noise) = (Self::std_errors(self.scatter, &matrix), Self::std_errors(self.noise, &matrix));
        let parameters = full_parameters(&matrix, &offset, [scatter, noise], self.inflation);
        Fit {
            model,
            matrix,
            offset,
            cost,
            iterations: 0,
            parameters,
            lines_used: pairs.iter().map(|p| p.line).collect(),
            noise_test: None,
            // NOTE: per reading axis, since each axis's residual variance is estimated on its own.
            warnings: uncertainty::redundancy_warnings(dataset, self.degrees_of_freedom),
            selection: None,
            prediction: self.reported().map(|c| prediction::linear(&matrix, &c, g)),
        }
    }
}

/// Refuses references that lie in one plane, naming the axis along which a position is missing.
fn check_spread(pairs: &[Pair], model: Model) -> Result<(), FitError> {
    let n = pairs.len() as f64;
    let mean = pairs.iter().fold(Vector3::zeros(), |sum, p| sum + Vector3::from(p.reference)) / n;
    let scatter = pairs.iter().fold(Matrix3::zeros(), |sum, p| {
        let d = Vector3::from(p.reference) - mean;
        sum + d * d.transpose()
    });
    let eigen = SymmetricEigen::new(scatter);
    let (smallest, _) = eigen.eigenvalues.argmin();
    let largest = eigen.eigenvalues.max();
    // NOTE: relative threshold: references are exact directions times g, so a plane shows as an
    // eigenvalue at rounding level, while any real spread is a sizeable fraction of the largest.
    if largest > 0.0 && eigen.eigenvalues[smallest] > 1e-9 * largest {
        return Ok(());
    }
    let normal = eigen.eigenvectors.column(smallest);
    let axis = normal.iamax();
    Err(FitError::ReferencesInOnePlane { model: model.name(), axis: ['x', 'y', 'z'][axis] })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::Row;
    use crate::fit::{fit, ModelChoice};
    use shared::orientation::from_inclination_toolface;

    const X: Mat3<f64> = [[1.021, 0.013, -0.004], [-0.007, 0.985, 0.009], [0.002, -0.011, 1.034]];
    const Y: Vec3<f64> = [0.0276, -0.0057, -0.0783];

    fn dataset(references: &[Vec3<f64>]) -> Dataset {
        let rows = references
            .iter()
            .enumerate()
            .map(|(i, &a)| {
                let reading = linalg::add(linalg::mul_vec(&X, a), Y);
                Row::new(i + 2, reading, Some(a))
            })
            .collect();
        Dataset { rows }
    }

    fn options() -> FitOptions {
        FitOptions { g: 1.0, ..FitOptions::default() }
    }

    #[test]
    fn linear12_recovers_a_known_model_from_tilted_noise_free_positions() {
        let references: Vec<_> =
            [(0.0, 0.0), (30.0, 45.0), (-40.0, 120.0), (60.0, 200.0), (-10.0, 300.0), (80.0, 10.0)]
                .iter()
                .map(|&(incl, tf)| from_inclination_toolface(incl, tf))
                .collect();
        let fit = fit(&dataset(&references), ModelChoice::Only(Model::Linear12), &options()).unwrap();
        let truth = linalg::inverse(&X).unwrap();
        assert!(linalg::max_abs_diff(&fit.matrix, &truth) < 1e-12);
        assert!(linalg::norm(linalg::sub(fit.offset, Y)) < 1e-12);
        assert!(fit.cost < 1e-24, "cost {}", fit.cost);
        // Noise-free data: the standard errors vanish with the residuals.
        assert!(fit.parameters.iter().all(|p| p.std_error.unwrap() < 1e-10));
    }

    #[test]
    fn linear12_refuses_fewer_than_four_references() {
        let data = dataset(&[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
        let error = fit(&data, ModelChoice::Only(Model::Linear12), &options()).unwrap_err();
        assert_eq!(error, FitError::TooFewReferences { model: "linear12", needed: 4, found: 3 });
    }

    #[test]
    fn references_in_one_plane_are_refused_naming_the_missing_axis() {
        // Every reference horizontal (z never up or down): the z column of X is not determined.
        let references: Vec<_> =
            [0.0, 60.0, 150.0, 200.0, 290.0].iter().map(|&tf| from_inclination_toolface(0.0, tf)).collect();
        let error = fit(&dataset(&references), ModelChoice::Only(Model::Linear12), &options()).unwrap_err();
        assert_eq!(error, FitError::ReferencesInOnePlane { model: "linear12", axis: 'z' });
        assert!(error.to_string().contains("add a position with the z axis pointing up or down"));
    }

    #[test]
    fn six_position_names_the_missing_face_and_a_repeated_one() {
        let faces: Vec<_> = Position::ALL.iter().map(|p| p.specific_force_g()).collect();
        let error = fit(&dataset(&faces[..5]), ModelChoice::Only(Model::SixPosition), &options()).unwrap_err();
        assert!(matches!(error, FitError::MissingPosition { position: Position::NegZ, .. }), "{error}");
        let mut repeated = faces.clone();
        repeated.insert(3, faces[0]);
        let error = fit(&dataset(&repeated), ModelChoice::Only(Model::SixPosition), &options()).unwrap_err();
        assert_eq!(error, FitError::DuplicatePosition { position: Position::PosX, first_line: 2, second_line: 5 });
    }
}
