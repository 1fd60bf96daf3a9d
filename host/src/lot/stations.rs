//! The lot across stations and days (issue 41): each group's own distributions and Cpk (its boards
//! by their latest certificate), and the stations that drift from the others: a station whose mean
//! of a parameter lies more than `STATION_DRIFT_STANDARD_ERRORS` from the other stations' together
//! (Welch's standard error of the difference of two means), each judged from
//! `STATION_DRIFT_MIN_BOARDS` boards on either side.

use std::collections::BTreeMap;

use serde::Serialize;

use super::{LotSummary, Spec};
use crate::certificate::Certificate;
use crate::limits::{STATION_DRIFT_MIN_BOARDS, STATION_DRIFT_STANDARD_ERRORS};

/// How `lot show --by` groups the boards.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Grouping {
    Station,
    /// The UTC day of the board's latest calibration.
    Day,
}

/// The lot by group, and the drifting stations.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Grouped {
    pub groups: Vec<Group>,
    /// Only when grouped by station.
    pub drifting: Vec<Drift>,
}

/// One station's or day's boards.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Group {
    pub name: String,
    pub summary: LotSummary,
}

/// A station's parameter that lies away from the other stations'.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Drift {
    pub station: String,
    pub parameter: String,
    pub unit: String,
    pub mean: f64,
    pub others_mean: f64,
    /// The difference in standard errors of the difference (signed).
    pub standard_errors: f64,
}

/// Every board's latest certificate and the station it came from, grouped.
pub fn grouped(all: &[(Certificate, String)], grouping: Grouping, spec: &Spec) -> Grouped {
    let mut latest: BTreeMap<&str, (&Certificate, &str)> = BTreeMap::new();
    for (certificate, station) in all {
        latest.insert(certificate.board.serial.as_deref().unwrap_or(""), (certificate, station));
    }
    let mut by_group: BTreeMap<String, Vec<Certificate>> = BTreeMap::new();
    for (certificate, station) in latest.values() {
        let name = match grouping {
            Grouping::Station => station.to_string(),
            Grouping::Day => certificate.date_utc.as_deref().unwrap_or("").chars().take(10).collect(),
        };
        by_group.entry(name).or_default().push((*certificate).clone());
    }
    let drifting = match grouping {
        Grouping::Station => drifting(&by_group),
        Grouping::Day => Vec::new(),
    };
    let groups =
        by_group.iter().map(|(name, c)| Group { name: name.clone(), summary: LotSummary::of(c, spec) }).collect();
    Grouped { groups, drifting }
}

/// Each station's parameters against the other stations' together.
fn drifting(by_station: &BTreeMap<String, Vec<Certificate>>) -> Vec<Drift> {
    let mut found = Vec::new();
    for (station, boards) in by_station {
        let others: Vec<&Certificate> = by_station.iter().filter(|(s, _)| *s != station).flat_map(|(_, c)| c).collect();
        for (name, p) in boards.first().map(|c| &c.parameters).into_iter().flatten() {
            let values = |set: &mut dyn Iterator<Item = &Certificate>| -> Vec<f64> {
                set.filter_map(|c| c.parameters.get(name).map(|p| p.value)).collect()
            };
            let (mine, theirs) = (values(&mut boards.iter()), values(&mut others.iter().copied()));
            if let Some(z) = difference_in_standard_errors(&mine, &theirs) {
                if z.abs() > STATION_DRIFT_STANDARD_ERRORS {
                    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
                    let (parameter, unit) = (name.clone(), p.unit.clone());
                    let (mean, others_mean) = (mean(&mine), mean(&theirs));
                    found.push(Drift {
                        station: station.clone(),
                        parameter,
                        unit,
                        mean,
                        others_mean,
                        standard_errors: z,
                    });
                }
            }
        }
    }
    found
}

/// (mean(a) - mean(b)) / sqrt(var(a)/n_a + var(b)/n_b), sample variances; none below the boards
/// needed on either side or without spread.
pub fn difference_in_standard_errors(a: &[f64], b: &[f64]) -> Option<f64> {
    if a.len() < STATION_DRIFT_MIN_BOARDS || b.len() < STATION_DRIFT_MIN_BOARDS {
        return None;
    }
    let moments = |v: &[f64]| {
        let n = v.len() as f64;
        let mean = v.iter().sum::<f64>() / n;
        (mean, v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0) / n)
    };
    let ((mean_a, var_mean_a), (mean_b, var_mean_b)) = (moments(a), moments(b));
    let standard_error = (var_mean_a + var_mean_b).sqrt();
    (standard_error > 0.0).then(|| (mean_a - mean_b) / standard_error)
}
