//! Who turns the board: the trait, and a person holding the board (instructions only). The tool's
//! own hand on the simulated board is beside it, in `simulated_hand`.

use super::{Feedback, Orientation, ProcedureError};

/// Who turns the board: a person, or the tool itself on the simulated board.
pub trait Hand {
    /// Turns (or asks to turn) the board to a wanted orientation.
    fn present(&mut self, target: &Orientation, feedback: &mut dyn Feedback) -> Result<(), ProcedureError>;
    /// Turns (or asks to turn) the board to a fresh orientation for verification.
    fn fresh(&mut self, index: usize, feedback: &mut dyn Feedback) -> Result<(), ProcedureError>;
    /// Turns (or asks to turn) the board a quarter turn over an edge, for the gyro's verification.
    fn turn_quarter(&mut self, feedback: &mut dyn Feedback) -> Result<(), ProcedureError>;
    /// Orientations (directions of up, any length) the fresh ones must keep away from; a person
    /// is told by the live line instead.
    fn avoid(&mut self, _orientations: &[[f64; 3]]) {}
    /// Whether the hand stops asking for positions, given whether `this_board` has enough: a hand
    /// on one board stops when it has; one turning a fixture of boards, once every board has.
    fn all_have_enough(&mut self, this_board: bool) -> bool {
        this_board
    }
}

/// A person holding the board: instructions only.
pub struct PersonHand;

impl Hand for PersonHand {
    fn present(&mut self, target: &Orientation, feedback: &mut dyn Feedback) -> Result<(), ProcedureError> {
        feedback.say(&format!(
            "Rest the board with {} pointing up ({}), and hold it still.",
            target.name,
            describe(target)
        ));
        Ok(())
    }

    fn turn_quarter(&mut self, feedback: &mut dyn Feedback) -> Result<(), ProcedureError> {
        feedback.say("Now turn the board a quarter turn (90 degrees) over one of its edges, and hold it still.");
        Ok(())
    }

    fn fresh(&mut self, index: usize, feedback: &mut dyn Feedback) -> Result<(), ProcedureError> {
        feedback.say(&format!(
            "Verification {}: rest the board in a new orientation, unlike the calibration positions and the ones verified, and hold it still.",
            index + 1
        ));
        Ok(())
    }
}

fn describe(target: &Orientation) -> String {
    match target.face_up() {
        Some(face) => format!("the {} axis printed on the board toward the sky", face.name()),
        None => "a corner up: tilt the board so that those three axes point equally upward".to_owned(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::orientation::Orientation;
    use crate::run::drift::closing;
    use crate::run::Told;

    #[test]
    fn the_closing_capture_of_a_face_is_described_as_that_face_not_as_a_corner() {
        let mut told = Told(Vec::new());
        let plus_z = Orientation::named("+Z").unwrap();
        PersonHand.present(&closing(&plus_z), &mut told).unwrap();
        PersonHand.present(&Orientation::named("+X-Y+Z").unwrap(), &mut told).unwrap();
        assert_eq!(
            told.0[0],
            "Rest the board with +Z again pointing up (the +Z axis printed on the board toward the sky), and hold it still."
        );
        assert!(told.0[1].contains("(a corner up: tilt the board"), "{}", told.0[1]);
    }
}
