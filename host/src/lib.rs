//! accelcal's host library, one module per concept:
//!
//! - [`link`]: the byte transports, the protocol client with one method per request, board discovery;
//! - [`sim`]: the host side of the simulation (the simulated board served over a port);
//! - [`procedure`]: the guided procedure (wanted orientations, the person's and the simulated hand,
//!   collecting captures, verification);
//! - [`part`]: the sensor part named for a person;
//! - [`orientation`]: the one type for a wanted orientation; [`limits`]: the host's thresholds;
//! - [`session`]: the captures of a calibration, kept as files;
//! - [`data`]: calibration data files;
//! - [`fit`]: least-squares fits;
//! - [`stream`]: a board's own stream as its sketch prints it (dialects, units, still periods);
//! - [`noise`]: noise characterisation of a still recording by Allan deviation;
//! - [`calibration`]: the device's calibration record on the host (its JSON form, from a fit);
//! - [`export`]: the calibration in other programs' formats, with what each loses;
//! - [`report`]: what a fit or a calibration reports, computed once, rendered as text or JSON;
//! - [`cli`]: the command line; the `accelcal` binary only calls [`cli::main`].
//!
//! `mutant` (crate-private) holds `mutant!`, the switch CI's guarded mutations break lines through
//! (docs/mutations.md).

// NOTE: first, so that every module below may use `mutant!` (a macro is in scope only after it).
#[macro_use]
mod mutant;

pub mod calibration;
pub mod certificate;
pub mod cli;
pub mod data;
pub mod error;
pub mod export;
pub mod files;
pub mod fit;
pub mod limits;
pub mod link;
pub mod lot;
pub mod noise;
pub mod orientation;
pub mod part;
pub mod procedure;
pub mod recording;
pub mod repeat;
pub mod report;
pub mod selftest;
pub mod session;
pub mod shown;
pub mod sim;
pub mod still;
pub mod stream;

pub use error::Error;
