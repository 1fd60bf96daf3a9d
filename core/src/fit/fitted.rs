//! What a fit is asked (`FitOptions`) and what it gives: the fit with its parameters and their
//! standard errors and, with `auto`, why that model (`Fit`, `Parameter`, `Selection`). Below the
//! choice among the models and the report; [`super::error`] says why a fit could not run.

use std::borrow::Cow;
use std::collections::HashSet;

use serde::Serialize;
use shared::linalg::{Mat3, Vec3};

use super::shape::{parameter_name, Shape};
use super::{FitError, Model, NoiseTest, Prediction};
use crate::data::Dataset;

/// Settings of a fit.
#[derive(Debug, Clone, PartialEq)]
pub struct FitOptions {
    /// |gravity| in output units (1 for g, 9.80665 for m/s^2).
    pub g: f64,
    /// Largest tilt in degrees for a reading to count as one of the six faces.
    pub face_tolerance_deg: f64,
    /// Data rows (1-based, in file order) to fit; `None`: all. The others are held out for testing.
    pub training_rows: Option<Vec<usize>>,
    /// Data rows (1-based) whose known orientation the fit uses; `None`: every row that has one.
    /// The other rows count as |a| = g only.
    pub reference_rows: Option<Vec<usize>>,
}

impl Default for FitOptions {
    fn default() -> Self {
        FitOptions {
            g: 1.0,
            face_tolerance_deg: crate::limits::FACE_TOLERANCE_DEG,
            training_rows: None,
            reference_rows: None,
        }
    }
}

impl FitOptions {
    /// The rows the fit sees: the training rows, with references only where they are to be used.
    pub(crate) fn training_set<'a>(&self, dataset: &'a Dataset) -> Result<Cow<'a, Dataset>, FitError> {
        let count = dataset.rows.len();
        for &row in self.training_rows.iter().chain(&self.reference_rows).flatten() {
            if row == 0 || row > count {
                return Err(FitError::NoSuchRow { row, rows: count });
            }
        }
        if self.training_rows.is_none() && self.reference_rows.is_none() {
            return Ok(Cow::Borrowed(dataset));
        }
        let set = |rows: &Option<Vec<usize>>| rows.as_ref().map(|r| r.iter().copied().collect::<HashSet<usize>>());
        let (training, references) = (set(&self.training_rows), set(&self.reference_rows));
        let rows = dataset
            .rows
            .iter()
            .enumerate()
            .filter(|(i, _)| training.as_ref().is_none_or(|rows| rows.contains(&(i + 1))))
            .map(|(i, row)| {
                let mut row = row.clone();
                if references.as_ref().is_some_and(|rows| !rows.contains(&(i + 1))) {
                    row.reference = None;
                }
                row
            })
            .collect();
        Ok(Cow::Owned(Dataset { rows }))
    }
}

/// One fitted parameter with its standard error (none when the fit has no redundancy to estimate it).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Parameter {
    /// Name: `M11` ... `M33` for a full matrix, `a_yz` ... `s_z` for T K, `o_x` ... `o_z` the offset.
    pub name: &'static str,
    /// Value (M dimensionless, o in the file's unit).
    pub value: f64,
    /// The standard error reported: the noise-based one, scaled up when the residuals are
    /// significantly larger than the noise explains, so that it holds whether the scatter comes from
    /// the noise or from what the model misses; the scatter-based one where the file gives no noise.
    pub std_error: Option<f64>,
    /// Standard error from the Jacobian and the residual scatter (none without redundancy).
    pub scatter_std_error: Option<f64>,
    /// Standard error from the noise the captures measured (`count`, `std_*`), where the data has it.
    pub noise_std_error: Option<f64>,
}

/// Parameters as every JSON report writes them (issue 40: `fit --json`, `report --json` and `calibrate
/// --json` had three forms): an object keyed by name, each `value`, `std_error`, `scatter_std_error`,
/// `noise_std_error`, as a certificate's `parameters` are keyed. Used with `#[serde(serialize_with)]`.
pub fn parameters_by_name<S: serde::Serializer>(parameters: &[Parameter], serializer: S) -> Result<S::Ok, S::Error> {
    /// One parameter's entry: its fields but the name, which is the key.
    #[derive(Serialize)]
    struct Entry {
        value: f64,
        std_error: Option<f64>,
        scatter_std_error: Option<f64>,
        noise_std_error: Option<f64>,
    }
    let entry = |p: &Parameter| Entry {
        value: p.value,
        std_error: p.std_error,
        scatter_std_error: p.scatter_std_error,
        noise_std_error: p.noise_std_error,
    };
    serializer.collect_map(parameters.iter().map(|p| (p.name, entry(p))))
}

impl Parameter {
    /// A parameter with its scatter- and noise-based standard errors; `inflation` scales the noise's
    /// for what the residuals show beyond the noise.
    pub(super) fn new(name: &'static str, value: f64, errors: [Option<f64>; 2], inflation: f64) -> Self {
        let [scatter_std_error, noise_std_error] = errors;
        let std_error = noise_std_error.map(|e| e * inflation).or(scatter_std_error);
        Parameter { name, value, std_error, scatter_std_error, noise_std_error }
    }
}

/// Standard errors of a full calibration's M and o.
type FullErrors = Option<(Mat3<f64>, Vec3<f64>)>;

/// Why `auto` chose its model, with every model's leave-one-out figure.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Selection {
    /// One sentence: the model chosen and the evidence.
    pub reason: String,
    /// Every model, richest first, with the RMS of | |a| - g | at each row left out of its fit, in
    /// output units; `None` where the model cannot be fitted with a row left out.
    pub leave_one_out: Vec<(&'static str, Option<f64>)>,
}

/// A fitted calibration: `a = matrix (m - offset)`, in the file's units.
#[derive(Debug, Clone, PartialEq)]
pub struct Fit {
    /// The model fitted.
    pub model: Model,
    /// Correction matrix M.
    pub matrix: Mat3<f64>,
    /// Offset o, in the file's unit.
    pub offset: Vec3<f64>,
    /// The model's dimensionless cost at the solution (residuals divided by g, squared, summed).
    pub cost: f64,
    /// Solver iterations: residual evaluations of the levenberg-marquardt crate, iterations of the
    /// fixed-size `ortho9` solver (one 9x9 solve each), 0 for closed-form fits.
    pub iterations: usize,
    /// Every parameter with its standard error.
    pub parameters: Vec<Parameter>,
    /// Data-file lines the fit used.
    pub lines_used: Vec<usize>,
    /// The residuals tested against the noise the captures measured, where the data carries it.
    pub noise_test: Option<NoiseTest>,
    /// Things the user should know: a poor condition number, a model that does not fit the noise.
    pub warnings: Vec<String>,
    /// With `auto`: why this model, and every model's leave-one-out figure.
    pub selection: Option<Selection>,
    /// The errors the parameters' uncertainty predicts at a fresh orientation.
    pub prediction: Option<Prediction>,
}

impl Fit {
    /// The fit of readings in g restated for the same readings in a unit of which `per_g` make a g:
    /// a = M (m - o) with m in g is (M / per_g) (m' - o per_g) with m' in the unit. M, `M11` ...
    /// `M33` and `s_x` ... `s_z` are divided by `per_g`, the offset `o_x` ... `o_z` multiplied, each
    /// with its standard errors; T's `a_*` and every figure in g (cost, residuals, prediction) stay.
    pub fn in_unit(mut self, per_g: f64) -> Fit {
        self.matrix = self.matrix.map(|row| row.map(|v| v / per_g));
        self.offset = self.offset.map(|v| v * per_g);
        for p in &mut self.parameters {
            let restate = |v: f64| restated(p.name, v, per_g);
            (p.value, p.std_error) = (restate(p.value), p.std_error.map(restate));
            (p.scatter_std_error, p.noise_std_error) =
                (p.scatter_std_error.map(restate), p.noise_std_error.map(restate));
        }
        self
    }
}

/// The value (or standard error) of the parameter `name` of a fit in g, for readings in a unit of
/// which `per_g` make a g: an offset's times `per_g`, a scale's divided by it, T's angles as they are.
fn restated(name: &str, value: f64, per_g: f64) -> f64 {
    match () {
        _ if name.starts_with("o_") => value * per_g,
        _ if name.starts_with("a_") => value,
        _ => value / per_g,
    }
}

/// Parameter list of a full 12-parameter calibration, with scatter- and noise-based standard errors
/// (the latter scaled by `inflation` where reported).
pub(super) fn full_parameters(
    matrix: &Mat3<f64>,
    offset: &Vec3<f64>,
    [scatter, noise]: [FullErrors; 2],
    inflation: f64,
) -> Vec<Parameter> {
    let name = |k: usize| parameter_name(Shape::Full, k);
    let mut parameters = Vec::with_capacity(12);
    for (i, row) in matrix.iter().enumerate() {
        for (j, &value) in row.iter().enumerate() {
            let (a, b) = (scatter.map(|(m, _)| m[i][j]), noise.map(|(m, _)| m[i][j]));
            parameters.push(Parameter::new(name(3 * i + j), value, [a, b], inflation));
        }
    }
    for (k, &value) in offset.iter().enumerate() {
        let (a, b) = (scatter.map(|(_, o)| o[k]), noise.map(|(_, o)| o[k]));
        parameters.push(Parameter::new(name(9 + k), value, [a, b], inflation));
    }
    parameters
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fit::ModelChoice;
    use shared::linalg::{mul_vec, sub};

    #[test]
    fn a_fit_restated_in_counts_corrects_counts_as_it_corrects_g_with_its_offset_and_scales_in_counts() {
        // NOTE: 16384 counts a g at +-2 g (MPU-6050 Product Specification 6.2).
        let per_g = 16384.0;
        let dataset = crate::sim::synthetic::random_positions(3, 18, 1e-4, true);
        for model in [Model::Ortho9, Model::Linear12] {
            let in_g = crate::fit::fit(&dataset, ModelChoice::Only(model), &FitOptions::default()).unwrap();
            let in_counts = in_g.clone().in_unit(per_g);
            for row in &dataset.rows {
                let a_g = mul_vec(&in_g.matrix, sub(row.reading, in_g.offset));
                let a_counts = mul_vec(&in_counts.matrix, sub(row.reading.map(|v| v * per_g), in_counts.offset));
                (0..3).for_each(|k| assert!((a_g[k] - a_counts[k]).abs() < 1e-12, "{model:?}: {a_g:?} {a_counts:?}"));
            }
            for (g, counts) in in_g.parameters.iter().zip(&in_counts.parameters) {
                let factor = match g.name {
                    "o_x" | "o_y" | "o_z" => per_g,
                    "a_yz" | "a_zy" | "a_zx" => 1.0,
                    _ => 1.0 / per_g,
                };
                assert!((counts.value - g.value * factor).abs() <= 1e-12 * (g.value * factor).abs(), "{}", g.name);
                let error = |p: &Parameter| p.std_error.unwrap();
                assert!((error(counts) - error(g) * factor).abs() <= 1e-12 * error(g) * factor, "{}", g.name);
            }
            assert_eq!((in_counts.cost, &in_counts.lines_used), (in_g.cost, &in_g.lines_used));
        }
    }
}
