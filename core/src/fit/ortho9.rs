//! `ortho9` through the shared fixed-size solver (the chip's own fit, run in f64): same minimum as the
//! levenberg-marquardt crate, several times faster; the statistics linearise at its solution.

use nalgebra::DVector;

use super::covariance::Square;
use super::linearised::Observation;
use super::nonlinear::Solution;
use super::shape::Shape;
use super::FitError;
use shared::ortho9::{self, Ortho9Error};

/// Whether the shared solver applies: `ortho9` with no reference rows and every row weighed alike (it
/// minimises the unweighted sum of (|a| - 1)^2; equal weights leave that minimum where it is).
pub(super) fn applies(shape: Shape, observations: &[Observation]) -> bool {
    let weight = observations.first().map_or(1.0, |o| o.weight);
    shape == Shape::TriangularTimesDiagonal && observations.iter().all(|o| o.reference.is_none() && o.weight == weight)
}

/// The `ortho9` problem minimised from M' = I, o' = 0, as the crate-based solve does, once `check`
/// has accepted J^T J at that start (the conditioning check, on the normal equations the solver's
/// first step solves anyway).
pub(super) fn solve(
    observations: &[Observation],
    check: impl FnOnce(&Square<{ ortho9::PARAMETERS }>) -> Result<(), FitError>,
) -> Result<Solution, FitError> {
    let readings: Vec<[f64; 3]> = observations.iter().map(|o| o.reading.into()).collect();
    let symmetric = |lower: &ortho9::StartNormal<f64>| Square::from_fn(|i, j| lower[i.max(j)][i.min(j)]);
    let fit = ortho9::fit_checked(&readings, ortho9::identity(), |lower| check(&symmetric(lower)))?;
    let params = DVector::from_row_slice(&fit.params);
    // NOTE: the cost of the weighted residuals, as the crate-based solve reports it (equal weights w
    // scale the unweighted cost by w^2).
    let weight = observations.first().map_or(1.0, |o| o.weight);
    let cost = fit.cost * weight * weight;
    Ok(Solution { params, cost, evaluations: fit.iterations as usize })
}

/// The host's error for the shared solver's refusal.
impl From<Ortho9Error> for FitError {
    fn from(error: Ortho9Error) -> Self {
        let model = super::Model::Ortho9.name();
        match error {
            Ortho9Error::TooFewReadings(found) => {
                FitError::TooFewPositions { model, needed: ortho9::MIN_READINGS, found: found.into() }
            }
            Ortho9Error::IllConditioned(k) => FitError::Unobservable {
                model,
                parameter: super::shape::parameter_name(Shape::TriangularTimesDiagonal, k.into()).to_owned(),
            },
            Ortho9Error::NotConverged => FitError::NotConverged {
                reason: format!("no negligible step in {} iterations", ortho9::MAX_ITERATIONS),
            },
            Ortho9Error::NotFinite => FitError::Degenerate,
        }
    }
}

#[cfg(test)]
mod tests {
    use nalgebra::Vector3;

    use super::*;
    use crate::data::{Dataset, Row};
    use crate::fit::models::observations;
    use crate::fit::normalization::Normalization;
    use crate::fit::observability::{check_conditioning, check_normal};
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
            let shared = solve(&observations, |_| Ok(())).unwrap();
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

    /// 24 positions pressed towards the great circle x + y + z = 0 (their component along (1, 1, 1)
    /// scaled by `squeeze`), read by a sensor of gain 1.01 and offset 0.02 g, every row alike.
    fn squeezed(squeeze: f64) -> Dataset {
        let rows = (0..24).map(|i| {
            let t = i as f64;
            let d = [(1.3 * t).sin(), (2.1 * t + 0.5).cos(), (0.7 * t + 1.0).sin()];
            let along = (d[0] + d[1] + d[2]) / 3.0 * (1.0 - squeeze);
            let d = Vector3::from(d.map(|x| x - along)).normalize();
            let mut row = Row::new(i + 2, (d * 1.01).add_scalar(0.02).into(), None);
            (row.count, row.std) = (Some(1000), Some([3e-3; 3]));
            row
        });
        Dataset { rows: rows.collect() }
    }

    #[test]
    fn the_check_on_the_solvers_normal_equations_judges_as_the_hosts_own_jacobian_does() {
        let shape = Shape::TriangularTimesDiagonal;
        let mut start = shape.identity();
        start.extend([0.0; 3]);
        let mut outcomes = Vec::new();
        for squeeze in [1.0, 3e-3, 1e-4] {
            let data = squeezed(squeeze);
            let observations = observations(&data, Model::Ortho9, &Normalization::of_dataset(&data), 1.0);
            let (mut by_host, mut by_solver) = (Vec::new(), Vec::new());
            let host = check_conditioning(Model::Ortho9, shape, &observations, &start, &mut by_host);
            let solver = solve(&observations, |n| check_normal(Model::Ortho9, shape, n, &mut by_solver));
            assert_eq!((solver.as_ref().err(), &by_solver), (host.as_ref().err(), &by_host), "squeeze {squeeze}");
            outcomes.push((solver.err(), by_solver));
        }
        // NOTE: well spread, nothing to say; pressed to 3e-3 of a circle, the cross-axis terms are
        // barely determined; to 1e-4, not at all.
        assert_eq!(outcomes[0], (None, vec![]));
        let warning =
            "poor condition number 3.5e4: the positions barely determine a_yz; add positions spread over the sphere";
        assert_eq!(outcomes[1], (None, vec![warning.to_owned()]));
        let refusal = FitError::Unobservable { model: "ortho9", parameter: "a_yz".to_owned() };
        assert_eq!(outcomes[2], (Some(refusal), vec![]));
    }
}
