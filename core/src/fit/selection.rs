//! `auto`: the model that best predicts rows it did not see (leave-one-out), with every model's
//! figure; and, where no model runs, the one the data came closest to supporting.

use super::left_out::leave_one_out_rms;
use super::{fit_model, Fit, FitError, FitOptions, Model, Selection, RICHEST_FIRST};
use crate::data::Dataset;

/// Fits every model and keeps the one with the smallest leave-one-out error; the richest that fits
/// when none can be judged that way; the closest refusal when none fits.
pub(super) fn choose(training: &Dataset, options: &FitOptions) -> Result<Fit, FitError> {
    let fits: Vec<(Model, Result<Fit, FitError>)> =
        RICHEST_FIRST.iter().map(|&m| (m, fit_model(training, m, options))).collect();
    let scores: Vec<(&'static str, Option<f64>)> = fits
        .iter()
        .map(|(m, r)| (m.name(), r.as_ref().ok().and_then(|_| leave_one_out_rms(training, *m, options))))
        .collect();
    let best = scores.iter().enumerate().filter_map(|(i, (_, s))| s.map(|s| (i, s))).min_by(|a, b| a.1.total_cmp(&b.1));
    let index = match best {
        Some((index, _)) => index,
        None => fits.iter().position(|(_, r)| r.is_ok()).ok_or_else(|| closest_refusal(&fits))?,
    };
    let reason = reason(&scores, index, options.g);
    let mut fit = fits.into_iter().nth(index).and_then(|(_, r)| r.ok()).ok_or(FitError::Degenerate)?;
    fit.selection = Some(Selection { reason, leave_one_out: scores });
    Ok(fit)
}

/// The sentence that says why model `index` was chosen.
fn reason(scores: &[(&'static str, Option<f64>)], index: usize, g: f64) -> String {
    let (name, score) = scores[index];
    let mg = |v: f64| v / g * 1000.0;
    match score {
        Some(score) => {
            let others: Vec<String> = scores
                .iter()
                .filter_map(|(n, s)| s.filter(|_| *n != name).map(|s| format!("{n} {:.3}", mg(s))))
                .collect();
            format!(
                "{name} predicts rows it did not see best: | |a| - g | {:.3} mg RMS left out one at a time \
                 (others: {})",
                mg(score),
                if others.is_empty() { "none could be tested".to_owned() } else { others.join(", ") }
            )
        }
        None => format!("{name} is the richest model that fits; no model can be tested on rows it did not see"),
    }
}

/// How many positions (or known orientations) a refusal says are missing: the distance from the
/// model.
fn shortfall(error: &FitError) -> usize {
    match error {
        FitError::TooFewPositions { needed, found, .. } | FitError::TooFewReferences { needed, found, .. } => {
            needed.saturating_sub(*found)
        }
        FitError::NoSpread { .. }
        | FitError::MissingPosition { .. }
        | FitError::ReferencesInOnePlane { .. }
        | FitError::DuplicatePosition { .. }
        | FitError::Unobservable { .. } => 1,
        _ => usize::MAX,
    }
}

/// What a refusal lacks in countable terms (" (2 positions short)"), or nothing when what it lacks is
/// not a count (a spread, an axis, a duplicate): its reason says that.
fn missing(error: &FitError) -> String {
    let count = |n: usize, noun: &str| format!(" ({n} {noun}{} short)", if n == 1 { "" } else { "s" });
    match error {
        FitError::TooFewPositions { needed, found, .. } => count(needed.saturating_sub(*found), "position"),
        FitError::TooFewReferences { needed, found, .. } => count(needed.saturating_sub(*found), "known orientation"),
        _ => String::new(),
    }
}

/// The refusal of the model the data came closest to (fewest positions short; the richer on a tie).
fn closest_refusal(fits: &[(Model, Result<Fit, FitError>)]) -> FitError {
    let closest = fits.iter().filter_map(|(m, r)| r.as_ref().err().map(|e| (*m, e))).min_by_key(|(_, e)| shortfall(e));
    match closest {
        Some((model, error)) => {
            FitError::NothingFits { closest: model.name(), short: missing(error), reason: error.to_string() }
        }
        None => FitError::Degenerate,
    }
}

#[cfg(test)]
mod shortfall_tests {
    use super::*;

    #[test]
    fn a_refusal_says_what_is_short_only_when_it_is_a_count() {
        let few = FitError::TooFewPositions { model: "ortho9", needed: 9, found: 7 };
        assert_eq!(missing(&few), " (2 positions short)");
        let references = FitError::TooFewReferences { model: "linear12", needed: 4, found: 3 };
        assert_eq!(missing(&references), " (1 known orientation short)");
        assert_eq!(missing(&FitError::NoSpread { model: "ortho9", axis: 'x', up: true }), "");
    }
}
