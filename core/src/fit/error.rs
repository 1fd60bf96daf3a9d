//! Why a fit could not run, each with what to add or change: below every solver, which all fail
//! with it.

use shared::Position;

/// Why a fit could not run; each says what to add or change.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FitError {
    #[error("{model} needs at least {needed} rows with a known orientation (ref_x,ref_y,ref_z); the file has {found}")]
    TooFewReferences { model: &'static str, needed: usize, found: usize },
    #[error("{model} needs at least {needed} positions; the data has {found}: add {} more", needed - found)]
    TooFewPositions { model: &'static str, needed: usize, found: usize },
    #[error(
        "the known orientations do not determine {model}: they lie in one plane; \
         add a position with the {axis} axis pointing up or down"
    )]
    ReferencesInOnePlane { model: &'static str, axis: char },
    #[error(
        "{model} cannot be determined: no position has the {axis} axis pointing {} (within {} degrees); \
         add one with {}{axis} up",
        if *up { "up" } else { "down" }, crate::limits::axis_spread_deg(), if *up { "+" } else { "-" }
    )]
    NoSpread { model: &'static str, axis: char, up: bool },
    #[error("{model} cannot be determined from these positions: {parameter} is not observable; add positions spread over the sphere")]
    Unobservable { model: &'static str, parameter: String },
    #[error(
        "six-position needs a reading with {} up (within {tolerance_deg} degrees); \
         add one, or choose a model that takes arbitrary positions",
        position.name()
    )]
    MissingPosition { position: Position, tolerance_deg: f64 },
    #[error("lines {first_line} and {second_line} are both {} up; keep one of them", position.name())]
    DuplicatePosition { position: Position, first_line: usize, second_line: usize },
    #[error("row {row} does not exist: the file has {rows} data rows")]
    NoSuchRow { row: usize, rows: usize },
    #[error("the solver did not converge ({reason}); check the file's unit and --g")]
    NotConverged { reason: String },
    #[error("the positions do not determine the sensor: opposite faces read alike (is the file's unit right?)")]
    Degenerate,
    #[error("no model can be fitted to these rows; the closest is {closest}{short}: {reason}")]
    NothingFits { closest: &'static str, short: String, reason: String },
}
