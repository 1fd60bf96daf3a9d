//! accelcal's host library: what touches files, ports, the clock, threads and the terminal, feeding
//! the I/O-free core ([`accelcal_core`]). The core's modules are re-exported here under their own
//! names (`fit`, `report`, `export`, `calibration`, `limits`, `orientation`, `shown`); where the host
//! adds I/O to one of the core's concepts, its module of that name re-exports the core's and adds
//! only that (`session`, `data`, `certificate`, `stream`, `noise`, `selftest`, `part`, `link`).
//! One module per concept:
//!
//! - [`link`]: the byte transports, the protocol client with one method per request, board discovery;
//! - [`sim`]: the host side of the simulation (the simulated board served over a port);
//! - [`opened`]: a board opened for a run (its connection, simulated board, seat, clock, hand);
//! - [`procedure`]: the guided procedure (wanted orientations, the person's and the simulated hand,
//!   collecting captures, verification);
//! - [`still`]: the mean of a raw stream from a board that must rest, or why it counts as moved;
//! - [`part`]: the sensor part named for a person, and its family confirmed by its offset registers;
//! - [`selftest`]: the datasheet self-test run from the host, and each board's self-test history;
//! - [`orientation`]: the one type for a wanted orientation; [`limits`]: the host's thresholds;
//! - [`session`]: the captures of a calibration, kept as files, and what they yield;
//! - [`files`]: files written so that a crash leaves the old or the new one, and the clock they carry;
//! - [`data`]: calibration data files;
//! - [`recording`]: long raw sample series in a NumPy `.npy` file;
//! - [`fit`]: least-squares fits;
//! - [`stream`]: a board's own stream as its sketch prints it (dialects, units, still periods);
//! - [`noise`]: noise characterisation of a still recording by Allan deviation;
//! - [`calibration`]: the device's calibration record on the host (its JSON form, from a fit);
//! - [`export`]: the calibration in other programs' formats, with what each loses;
//! - [`certificate`]: a board's calibration certificate, its uncertainty budget and its seal;
//! - [`ended`]: what a session leaves when its run ends (verified: its certificate, report page and
//!   row in a lot; stopped: the command that goes on with it);
//! - [`lot`]: every board's certificates in one SQLite file, and the lot's summary;
//! - [`repeat`]: N calibrations of one simulated board, the spread beside the predicted errors;
//! - [`sections`]: a session report's sections read from other commands' files;
//! - [`report`]: what a fit or a calibration reports, computed once, rendered as text, JSON or HTML;
//! - [`shown`]: how a number, a date or a text is shown to a person;
//! - [`error`]: the library's top error, wrapping each layer's own;
//! - [`terminal`]: a person at a terminal (progress, questions, Ctrl-C, spinners);
//! - [`cli`]: the command line; the `accelcal` binary only calls [`cli::main`].
//!
//! `mutant!` (the core's) is the switch CI's guarded mutations break lines through
//! (docs/mutations.md).

// NOTE: first, so that every module below may use the core's `mutant!`.
#[macro_use]
extern crate accelcal_core;

pub mod certificate;
pub mod cli;
pub mod data;
pub mod ended;
pub mod error;
pub mod files;
pub mod link;
pub mod lot;
pub mod noise;
pub mod opened;
pub mod part;
pub mod procedure;
pub mod recording;
pub mod records;
pub mod repeat;
pub mod sections;
pub mod selftest;
pub mod session;
pub mod sim;
pub mod still;
pub mod stream;
pub mod terminal;
pub mod web;

pub use accelcal_core::{calibration, export, fit, limits, orientation, report, shown};
pub use error::Error;
