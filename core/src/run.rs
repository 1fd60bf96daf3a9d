//! The calibration run: how a session is begun, collected, fitted, uploaded, verified, certified,
//! resumed and interrupted, as decisions fed what arrived and the time.

pub mod drift;
