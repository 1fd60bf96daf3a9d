//! A hand's turn of the simulated board: a real rotation at a smoothly rising and falling rate, as
//! brisk as a person following instructions, so that the gyro sees it. Used by the tool's own hand
//! and by a person typing into `sim --pty`.

use firmware::sim::physics::Motion;
use shared::linalg::{cross, norm, scale};
use shared::orientation::angle_between_deg;

use super::command::SimCommand;

/// How long a hand takes for a turn: this many seconds, plus one per [`HAND_TURN_DPS`] degrees.
///
/// NOTE: a quarter turn in 1.2 s peaks at 150 deg/s, a half turn in 1.8 s at 200 deg/s: the brisk
/// but unhurried turn of a person following instructions.
const HAND_TURN_BASE_S: f64 = 0.6;
const HAND_TURN_DPS: f64 = 150.0;

/// The board turned by `angle_deg` about the body `axis` (any length, not zero), at a hand's pace,
/// then at rest; a negative angle turns the other way.
pub fn turning(axis: [f64; 3], angle_deg: f64) -> SimCommand {
    let axis = scale(axis, angle_deg.signum() / norm(axis));
    let angle_deg = angle_deg.abs();
    let seconds = (HAND_TURN_BASE_S + angle_deg / HAND_TURN_DPS) as f32;
    let motion = Motion::Turning { axis: axis.map(|v| v as f32), angle_deg: angle_deg as f32, seconds };
    SimCommand::MoveFor { motion, seconds }
}

/// The turn that carries the body's up from `from` to `to` about the line perpendicular to both
/// (horizontal all the way); a half turn goes about the horizontal line across `from` and `aside`
/// (or, along `from`, about one of the body's x and y axes).
pub fn turn_between(from: [f64; 3], to: [f64; 3], aside: [f64; 3]) -> SimCommand {
    let perpendicular = |v: &[f64; 3]| norm(*v) > 1e-6;
    let half_turn_axes = [aside, [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]].map(|a| cross(from, a));
    let axis = Some(cross(to, from)).filter(perpendicular).or_else(|| half_turn_axes.into_iter().find(perpendicular));
    turning(axis.unwrap_or([1.0, 0.0, 0.0]), angle_between_deg(from, to))
}

/// A turn by `angle_deg` over an edge of a board resting with `up` up: about the horizontal line
/// across the board's x axis (its y axis when x points up).
pub fn tip(up: [f64; 3], angle_deg: f64) -> SimCommand {
    let across = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]].map(|a| cross(up, a));
    let axis = if norm(across[0]) > 0.5 { across[0] } else { across[1] };
    turning(axis, angle_deg)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tip_turns_about_a_horizontal_line_wherever_the_board_rests() {
        let r = 1.0 / 3f64.sqrt();
        for up in [[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [-1.0, 0.0, 0.0], [r, r, r], [0.6, 0.0, 0.8]] {
            let SimCommand::MoveFor { motion: Motion::Turning { axis, angle_deg, .. }, .. } = tip(up, 90.0) else {
                panic!("a tip is a turn");
            };
            let along_up: f64 = (0..3).map(|k| f64::from(axis[k]) * up[k]).sum();
            assert!(along_up.abs() < 1e-6 && angle_deg == 90.0, "{up:?}: axis {axis:?}");
        }
    }
}
