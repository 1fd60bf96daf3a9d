//! The person's hand in the page: the core's instructions (`PersonHand`'s words) shown as the prompt,
//! with what the automation hooks need beside them (the wanted orientation's name and up direction).

use accelcal_core::run::{Feedback, Hand, Orientation, PersonHand, ProcedureError, Told};

use super::page::PageUi;

/// A person holding the board, told by the page.
pub struct PromptHand {
    /// The page, shared with the run's feedback.
    pub ui: PageUi,
}

impl PromptHand {
    /// What the person's hand says for one step: the core's own line, so the page and the terminal agree.
    fn line(
        step: impl FnOnce(&mut PersonHand, &mut Told) -> Result<(), ProcedureError>,
    ) -> Result<String, ProcedureError> {
        let mut told = Told(Vec::new());
        step(&mut PersonHand, &mut told)?;
        Ok(told.0.join(" "))
    }
}

impl Hand for PromptHand {
    fn present(&mut self, target: &Orientation, _: &mut dyn Feedback) -> Result<(), ProcedureError> {
        let line = Self::line(|hand, told| hand.present(target, told))?;
        self.ui.prompt("present", &target.name, &target.up, 0, &line);
        Ok(())
    }

    fn fresh(&mut self, index: usize, _: &mut dyn Feedback) -> Result<(), ProcedureError> {
        let line = Self::line(|hand, told| hand.fresh(index, told))?;
        // NOTE: an index past u32 is beyond any verification count (at most 255, `--verify`).
        self.ui.prompt("fresh", "", &[], index as u32, &line);
        Ok(())
    }

    fn turn_quarter(&mut self, _: &mut dyn Feedback) -> Result<(), ProcedureError> {
        let line = Self::line(|hand, told| hand.turn_quarter(told))?;
        self.ui.prompt("quarter", "", &[], 0, &line);
        Ok(())
    }

    fn avoid(&mut self, orientations: &[[f64; 3]]) {
        let flat: Vec<f64> = orientations.iter().flatten().copied().collect();
        self.ui.avoid(&flat);
    }
}
