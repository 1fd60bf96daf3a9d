//! The simulated person and sketches, random draws and synthetic data sets: for tests and the
//! simulated runs (house rule 13: simulated things live in `sim`).

pub mod person;
pub mod random;
pub mod sessions;
pub mod sketch;
pub mod synthetic;
