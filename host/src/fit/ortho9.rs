//! `ortho9` through the shared fixed-size solver (the chip's own fit, run in f64): same minimum as the
//! levenberg-marquardt crate, several times faster; the statistics linearise at its solution.

use nalgebra::DVector;

use super::nonlinear::{Observation, Solution};
use super::shape::Shape;
use super::FitError;
use shared::ortho9::{self, Ortho9Error};

/// Whether the shared solver applies: `ortho9` with no reference rows and every row weighed alike (it
/// minimises the unweighted sum of (|a| - 1)^2; equal weights leave that minimum where it is).
pub(super) fn applies(shape: Shape, observations: &[Observation]) -> bool {
    let weight = observations.first().map_or(1.0, |o| o.weight);
    shape == Shape::TriangularTimesDiagonal && observations.iter().all(|o| o.reference.is_none() && o.weight == weight)
}

/// The shared solver's solution where it applies, else `otherwise`'s (the crate-based solve).
pub(super) fn solve_or(
    shape: Shape,
    observations: &[Observation],
    otherwise: impl FnOnce() -> Result<Solution, FitError>,
) -> Result<Solution, FitError> {
    if applies(shape, observations) {
        solve(observations)
    } else {
        otherwise()
    }
}

/// Minimises the `ortho9` problem from M' = I, o' = 0, as the crate-based solve does.
pub(super) fn solve(observations: &[Observation]) -> Result<Solution, FitError> {
    let readings: Vec<[f64; 3]> = observations.iter().map(|o| o.reading.into()).collect();
    let fit = ortho9::fit(&readings).map_err(fit_error)?;
    let params = DVector::from_row_slice(&fit.params);
    // NOTE: the cost of the weighted residuals, as the crate-based solve reports it (equal weights w
    // scale the unweighted cost by w^2).
    let weight = observations.first().map_or(1.0, |o| o.weight);
    let cost = fit.cost * weight * weight;
    Ok(Solution { params, cost, evaluations: fit.iterations as usize })
}

/// The host's error for the shared solver's refusal.
fn fit_error(error: Ortho9Error) -> FitError {
    let model = super::Model::Ortho9.name();
    match error {
        Ortho9Error::TooFewReadings(found) => {
            FitError::TooFewPositions { model, needed: ortho9::MIN_READINGS, found: found.into() }
        }
        Ortho9Error::IllConditioned(k) => FitError::Unobservable {
            model,
            parameter: super::models::parameter_name(Shape::TriangularTimesDiagonal, k.into()),
        },
        Ortho9Error::NotConverged => {
            FitError::NotConverged { reason: format!("no negligible step in {} iterations", ortho9::MAX_ITERATIONS) }
        }
        Ortho9Error::NotFinite => FitError::Degenerate,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fit::models::observations;
    use crate::fit::normalization::Normalization;
    use crate::fit::{nonlinear, Model};
    use crate::sim::synthetic::random_positions;

    #[test]
    fn the_shared_solver_reaches_the_crates_minimum_to_f64_rounding_on_120_problems() {
        let shape = Shape::TriangularTimesDiagonal;
        let mut worst = 0.0f64;
        for seed in 0..120 {
            let data = random_positions(500 + seed, 9 + (seed as usize % 16), 1e-4, false);
            let readings: Vec<[f64; 3]> = data.rows.iter().map(|r| r.reading).collect();
            let observations = observations(&data, Model::Ortho9, &Normalization::from_readings(&readings), 1.0);
            let mut start = shape.identity();
            start.extend([0.0; 3]);
            let by_crate = nonlinear::solve(shape, &observations, DVector::from_vec(start)).unwrap();
            let shared = solve(&observations).unwrap();
            for (k, (ours, theirs)) in shared.params.iter().zip(by_crate.params.iter()).enumerate() {
                // NOTE: relative to the parameter, with 1e-3 as the scale of the cross-axis terms
                // (the largest are a few 1e-3), so a zero crossing does not inflate the ratio.
                let relative = (ours - theirs).abs() / theirs.abs().max(1e-3);
                assert!(relative < 1e-9, "seed {seed} parameter {k}: {ours} vs {theirs}");
                worst = worst.max(relative);
            }
            // NOTE: nine positions fit exactly, to a cost at the rounding floor (about 1e-31).
            assert!(
                (shared.cost - by_crate.cost).abs() <= 1e-9 * by_crate.cost + 1e-28,
                "seed {seed}: {} vs {}",
                shared.cost,
                by_crate.cost
            );
        }
        println!("shared ortho9 vs levenberg-marquardt crate over 120 problems: worst relative {worst:.2e}");
    }
}
