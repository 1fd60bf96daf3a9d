//! The next capture a collection's plan asks for: below both the loop (`collect`) and the orders
//! that fill it in (`adaptive`).

use super::Orientation;

/// The next capture a plan asks for: the positions it takes (the first is the one asked for), those
/// already taken (named when the board comes back to one), and whether it closes an adaptive session.
pub(super) struct Wanted {
    pub(super) positions: Vec<Orientation>,
    pub(super) done: Vec<Orientation>,
    pub(super) closing: bool,
}
