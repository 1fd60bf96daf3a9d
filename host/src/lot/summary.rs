//! The lot at a glance: each certified parameter's distribution over the boards (each board's latest
//! certificate), its process capability Cpk against the spec's limits, and the boards outside them.

use std::collections::BTreeMap;

use serde::Serialize;

use super::{Limits, Spec};
use crate::certificate::Certificate;

/// The lot's distributions and the boards outside the spec.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LotSummary {
    /// Boards in the lot (each counted once, by its latest certificate).
    pub boards: usize,
    /// Their serials.
    pub serials: Vec<String>,
    pub parameters: Vec<Distribution>,
    /// Serial -> the parameters outside their limits.
    pub outside: BTreeMap<String, Vec<String>>,
}

/// One parameter over the lot, in the certificate's unit.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Distribution {
    pub name: String,
    pub unit: String,
    /// Boards whose certificate states it.
    pub boards: usize,
    pub mean: f64,
    /// Sample standard deviation over the boards (null below two boards).
    pub std: Option<f64>,
    pub min: f64,
    pub max: f64,
    /// The largest expanded uncertainty (k = 2) a board's certificate states for it.
    pub max_expanded: f64,
    pub limits: Option<Limits>,
    /// min(high - mean, mean - low) / (3 std) over the limits given; null without limits or spread.
    pub cpk: Option<f64>,
    /// Serials of the boards outside the limits.
    pub outside: Vec<String>,
}

impl LotSummary {
    /// The summary of the boards' latest certificates against the spec.
    pub fn of(latest: &[Certificate], spec: &Spec) -> Self {
        let mut by_name: BTreeMap<&str, Vec<(&str, f64, f64, &str)>> = BTreeMap::new();
        for certificate in latest {
            let serial = certificate.board.serial.as_deref().unwrap_or("");
            for (name, p) in &certificate.parameters {
                by_name.entry(name).or_default().push((serial, p.value, p.expanded, &p.unit));
            }
        }
        let parameters: Vec<Distribution> =
            by_name.iter().map(|(name, boards)| Distribution::of(name, boards, spec.limits.get(*name))).collect();
        let mut outside: BTreeMap<String, Vec<String>> = BTreeMap::new();
        for distribution in &parameters {
            for serial in &distribution.outside {
                outside.entry(serial.clone()).or_default().push(distribution.name.clone());
            }
        }
        let serials = latest.iter().map(|c| c.board.serial.clone().unwrap_or_default()).collect();
        LotSummary { boards: latest.len(), serials, parameters, outside }
    }
}

impl Distribution {
    /// One parameter's distribution from (serial, value, U, unit) per board.
    fn of(name: &str, boards: &[(&str, f64, f64, &str)], limits: Option<&Limits>) -> Self {
        let values: Vec<f64> = boards.iter().map(|b| b.1).collect();
        let (mean, std) = mean_and_std(&values);
        let outside = match limits {
            Some(limits) => boards
                .iter()
                .filter(|b| mutant!("lot-outside-inverted", !limits.admits(b.1), limits.admits(b.1)))
                .map(|b| b.0.to_owned())
                .collect(),
            None => Vec::new(),
        };
        Distribution {
            name: name.to_owned(),
            unit: boards.first().map_or("", |b| b.3).to_owned(),
            boards: boards.len(),
            mean,
            std,
            min: values.iter().copied().fold(f64::INFINITY, f64::min),
            max: values.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            max_expanded: boards.iter().map(|b| b.2).fold(0.0, f64::max),
            limits: limits.copied(),
            cpk: limits.and_then(|limits| cpk(mean, std?, limits)),
            outside,
        }
    }
}

/// The mean and the sample standard deviation (n - 1; none below two values).
fn mean_and_std(values: &[f64]) -> (f64, Option<f64>) {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let std = (values.len() >= 2).then(|| {
        (values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / mutant!("lot-std-population", n - 1.0, n)).sqrt()
    });
    (mean, std)
}

/// Cpk: the distance from the mean to the nearer limit in units of three standard deviations
/// (with one limit, that side's Cpu or Cpl); none when the boards do not spread.
pub fn cpk(mean: f64, std: f64, limits: &Limits) -> Option<f64> {
    let above = limits.high.map(|high| (high - mean) / (3.0 * std));
    let below = limits.low.map(|low| mutant!("lot-cpk-below-sign", mean - low, low - mean) / (3.0 * std));
    let nearer = [above, below].into_iter().flatten().fold(f64::INFINITY, f64::min);
    (std > 0.0 && nearer.is_finite()).then_some(nearer)
}
