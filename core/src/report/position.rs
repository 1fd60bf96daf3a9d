//! One captured position as the report shows it: below the session report that lists them and the
//! figures drawn of them.

use serde::Serialize;
use shared::linalg;

/// One captured position, in g, and its residual | |v| - 1 g | in mg (signed).
#[derive(Debug, Clone, Serialize)]
pub struct PositionResult {
    /// The capture's name.
    pub name: String,
    /// The raw mean reading, in g.
    pub raw_g: [f64; 3],
    /// The calibrated reading, in g.
    pub calibrated_g: [f64; 3],
    /// |raw| - 1 g, in mg.
    pub residual_before_mg: f64,
    /// |calibrated| - 1 g, in mg.
    pub residual_after_mg: f64,
}

/// |v| - 1 g, in mg, for v in g.
pub fn residual_mg(v: [f64; 3]) -> f64 {
    (linalg::norm(v) - 1.0) * 1000.0
}
