//! The calibration run: how a session is begun, collected, fitted, uploaded, verified, certified,
//! resumed and interrupted, as decisions fed what arrived and the time: the order that measures a
//! drift ([`drift`]), how a run ended and whether it certifies ([`ending`]), and what a resumed run
//! keeps and claims ([`resume`]).

pub mod drift;
pub mod ending;
pub mod resume;
