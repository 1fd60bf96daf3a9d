//! accelcal's core: everything that decides, free of I/O. It reads no file, port or clock, starts no
//! thread and controls no process: it is fed what arrived (bytes from a board, lines of a sketch's
//! stream, a person's answers) with the time the host read it, and returns what to send, what to tell
//! the person and what to keep. The command line (`accelcal`) and the web page are its hosts.
//!
//! - [`run`]: the calibration run (the order that measures a drift, ...);
//! - [`link`]: the wire's decisions (frames out under their ids, answers in, silence judged by
//!   frames at the times the host gives), what can go wrong on it and each device error in words;
//! - [`session`]: a session's captures and what it yields ([`session::Session::outcome`]);
//! - [`fit`]: least-squares fits, their statistics and the drift and thermal models;
//! - [`calibration`]: the device's calibration record on the host (its JSON form, from a fit);
//! - [`data`]: calibration data (typed rows, the CSV text);
//! - [`stream`]: a board's own stream as its sketch prints it (dialects, units, still periods);
//! - [`noise`]: noise characterisation by Allan deviation;
//! - [`report`]: what a fit, a session or a stream reports, computed once, rendered as text, JSON or HTML;
//! - [`export`]: the calibration in other programs' formats, with what each loses;
//! - [`certificate`]: a board's calibration certificate (budget, expanded uncertainties, seal);
//! - [`selftest`]: a self-test's result and its report; [`part`]: the sensor part named for a person;
//! - [`orientation`]: the one type for a wanted orientation; [`limits`]: the thresholds, each with its
//!   reason; [`shown`]: how a number, a date or a text is shown;
//! - [`mutant`]: `mutant!`, the switch CI's guarded mutations break lines through (feature `mutants`);
//! - [`sim`] (feature `sim`): the simulated person and sketches, and synthetic data sets.

// NOTE: first, so that every module below may use `mutant!` (a macro is in scope only after it).
#[macro_use]
pub mod mutant;

pub mod calibration;
pub mod certificate;
pub mod data;
pub mod export;
pub mod fit;
pub mod limits;
pub mod link;
pub mod noise;
pub mod orientation;
pub mod part;
pub mod report;
pub mod run;
pub mod selftest;
pub mod session;
pub mod shown;
#[cfg(feature = "sim")]
pub mod sim;
pub mod stream;
