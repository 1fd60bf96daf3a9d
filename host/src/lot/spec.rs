//! The lot's spec file: limits per certified parameter, in the certificate's own units (g for the
//! offsets, g/degC for the drift slopes, 1 for the matrix), as TOML:
//!
//! ```toml
//! [limits.o_x]
//! low = -0.05
//! high = 0.05
//! ```

use std::collections::BTreeMap;
use std::path::Path;

use serde::{Deserialize, Serialize};

use super::LotError;

/// Limits per parameter name.
#[derive(Debug, Clone, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Spec {
    pub limits: BTreeMap<String, Limits>,
}

/// A parameter's lower and upper specification limits (either may be absent).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Limits {
    pub low: Option<f64>,
    pub high: Option<f64>,
}

impl Limits {
    /// Whether a value lies within the limits.
    pub fn admits(&self, value: f64) -> bool {
        self.low.is_none_or(|low| value >= low) && self.high.is_none_or(|high| value <= high)
    }
}

impl Spec {
    /// Reads and checks a spec file: every limit finite, at least one per parameter, low below high.
    pub fn load(path: &Path) -> Result<Self, LotError> {
        let refused = |reason: String| LotError::Spec { path: path.into(), reason };
        let text = std::fs::read_to_string(path).map_err(|e| refused(e.to_string()))?;
        let spec: Spec = toml::from_str(&text).map_err(|e| refused(e.to_string()))?;
        spec.limits.iter().try_for_each(|(name, limits)| limits.check(name)).map_err(refused)?;
        Ok(spec)
    }

    /// Refuses limits for parameters no certificate of the lot states (a misspelt name).
    pub fn check_names<'a>(
        &self,
        path: &Path,
        stated: impl Iterator<Item = &'a String> + Clone,
    ) -> Result<(), LotError> {
        match self.limits.keys().find(|name| !stated.clone().any(|s| s == *name)) {
            Some(unknown) => {
                let known: Vec<&str> = stated.map(String::as_str).collect();
                let reason =
                    format!("no certificate in the lot states `{unknown}`; the parameters are {}", known.join(", "));
                Err(LotError::Spec { path: path.into(), reason })
            }
            None => Ok(()),
        }
    }
}

impl Limits {
    fn check(&self, name: &str) -> Result<(), String> {
        match (self.low, self.high) {
            (None, None) => Err(format!("`{name}` has neither `low` nor `high`")),
            (Some(low), Some(high)) if low.is_nan() || high.is_nan() || low >= high => {
                Err(format!("`{name}`: low {low} is not below high {high}"))
            }
            (Some(limit), None) | (None, Some(limit)) if !limit.is_finite() => {
                Err(format!("`{name}`: {limit} is no limit"))
            }
            _ => Ok(()),
        }
    }
}
