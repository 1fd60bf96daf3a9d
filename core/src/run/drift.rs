//! The order that measures a slow drift during a session (the first position again at the end,
//! A ... Z ... A); the drift per degree itself is fitted in [`crate::fit::drift`].

use crate::fit::drift::span_c;
use crate::limits::{DRIFT_MIN_CAPTURES, DRIFT_MIN_CHANGE_C};
use crate::orientation::Orientation;
use crate::session::Session;

/// The order in which the adaptive procedure asks for positions, chosen among orders from +Z for the
/// least error that a linear drift leaves in the twelve-parameter fit of all fourteen (and of the
/// first thirteen), at the session's end temperature, with the time a hand takes to turn counted:
/// most turns are 55-70 degrees (a face to a neighbouring corner, or a corner to the next), the
/// corners come first around the top and the bottom, the faces last.
// NOTE: the order before this one alternated faces and corners (125 degree turns); over the 20
// simulated sessions of tests/one_minute.rs it kept the board up to 63.2 s (this one 57.8 s) and
// ended 0.372 mg rms off at the end temperature (this one 0.297 mg). The search is
// host/tools/drift_order.py.
const ORDER: [&str; 14] = [
    "+Z", "+X-Y+Z", "+X+Y+Z", "+X+Y-Z", "-X+Y-Z", "-X-Y-Z", "-X-Y+Z", "+X-Y-Z", "-Z", "-X", "-Y", "+X", "+Y", "-X+Y+Z",
];
/// What the closing capture of the first position is called after it (a name for people: the
/// capture carries its own mark).
const AGAIN: &str = " again";

/// The wanted orientations in drift-cancelling order (those not in the table keep their place at
/// the end).
pub fn order(targets: &[Orientation]) -> Vec<Orientation> {
    let rank = |t: &Orientation| ORDER.iter().position(|n| *n == t.name).unwrap_or(ORDER.len());
    let mut ordered = targets.to_vec();
    ordered.sort_by_key(rank);
    ordered
}

/// The closing capture's orientation: the first position again, under its own name (the capture
/// itself is marked [`crate::session::CaptureRecord::closing`]).
pub fn closing(first: &Orientation) -> Orientation {
    Orientation { name: format!("{}{AGAIN}", first.name), ..first.clone() }
}

/// Whether the temperature moved enough for a drift, yet the captures would still be too few to fit
/// it after `more` further captures (never with a learned temperature model, which is kept).
pub fn unfitted_after(session: &Session, more: usize) -> bool {
    let span_c = span_c(&session.dataset());
    session.learned.is_none()
        && span_c.1 - span_c.0 >= DRIFT_MIN_CHANGE_C
        && session.captures.len() + more < DRIFT_MIN_CAPTURES
}

#[cfg(test)]
mod tests {
    use shared::linalg;

    use super::*;
    use crate::orientation::{corners, faces};
    use crate::session::CaptureRecord;

    /// A noise-free capture of a sensor with M^-1 = diag(1.01, 0.99, 1.02) plus a cross term, offset
    /// o(T) = o + c (T - 22), at `up` and die temperature `temp_c`.
    fn capture(target: &Orientation, temp_c: f64, slope: [f64; 3], std_g: f32) -> CaptureRecord {
        let sensor = [[1.01, 0.002, -0.004], [0.0, 0.99, 0.003], [0.0, 0.0, 1.02]];
        let offset = [0.03, -0.01, -0.08];
        let reading =
            linalg::add(linalg::mul_vec(&sensor, target.up), linalg::add(offset, linalg::scale(slope, temp_c - 22.0)));
        CaptureRecord::still(target, reading, std_g, 200, temp_c)
    }

    /// Noise-free captures that state a scatter of `std_g` per sample (200 samples each).
    fn warming_session(slope: [f64; 3], std_g: f32) -> Session {
        let mut targets = order(&[faces(), corners()].concat());
        targets.push(closing(&targets[0]));
        let captures = targets.iter().enumerate().map(|(i, t)| capture(t, 21.5 + 0.07 * i as f64, slope, std_g));
        Session { captures: captures.collect(), ..Session::default() }
    }

    #[test]
    fn a_drift_is_awaited_while_the_captures_are_too_few_to_fit_it() {
        let mut still = warming_session([1e-3; 3], 2.8e-3);
        still.captures.iter_mut().for_each(|c| c.stats.temp_c = 25.0);
        let mut few = warming_session([1e-3; 3], 2.8e-3);
        few.captures.truncate(DRIFT_MIN_CAPTURES - 1);
        // One capture short: the closing one makes it fitted; a board that stayed needs none.
        assert!(unfitted_after(&few, 0) && !unfitted_after(&few, 1));
        assert!(!unfitted_after(&still, 0));
    }

    #[test]
    fn the_order_is_the_table_s_and_closes_on_its_first_position() {
        let ordered = order(&[faces(), corners()].concat());
        let names: Vec<&str> = ordered.iter().map(|t| t.name.as_str()).collect();
        assert_eq!(names, ORDER);
        assert_eq!(closing(&ordered[0]).name, "+Z again");
        assert_eq!(closing(&ordered[0]).up, ordered[0].up);
    }
}
