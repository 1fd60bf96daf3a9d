//! The family check in words, as `info` and `selftest` print it.

use super::check::{FamilyCheck, Verdict};
use super::family_name;
use super::offsets::OffsetStep;

impl FamilyCheck {
    /// The check in words, one line.
    pub fn summary(&self) -> String {
        summary(self)
    }
}

/// One line: the verdict, what each step did, and the way on when it is not a confirmation.
fn summary(check: &FamilyCheck) -> String {
    let family = family_name(check.family);
    let steps = steps_text(&check.steps);
    match check.verdict {
        Verdict::Confirmed => format!("{family} family, confirmed by its offset registers ({steps})"),
        Verdict::ContradictsWhoAmI { claimed } => format!(
            "{family} family, confirmed by its offset registers ({steps}): not the {} family its WHO_AM_I claims",
            family_name(claimed)
        ),
        Verdict::ContradictsReadBack { by_offsets } => format!(
            "NOT confirmed: its offset registers are the {} family's ({steps}), its other registers the {family} family's; report it with `accelcal info --registers`",
            family_name(by_offsets)
        ),
        Verdict::OffsetsIgnored => format!(
            "NOT confirmed: neither family's offset register moved the output ({steps}); the {family} family's does on a genuine part"
        ),
        Verdict::Unclear => format!("NOT confirmed: its offset registers move the output as no family's do ({steps})"),
        Verdict::BoardMoved => format!(
            "not checked: the board moved during each of {} attempts ({}); rest it on a table and run again",
            check.attempts,
            check.moved.as_deref().unwrap_or("")
        ),
    }
}

/// "0x06 (MPU-6050) stepped -125.0 mg: x moved +0.2 mg; 0x77 (MPU-6500) stepped +125.0 mg: ...".
fn steps_text(steps: &[OffsetStep]) -> String {
    let step = |s: &OffsetStep| {
        format!(
            "0x{:02x} ({}) stepped {:+.1} mg: x moved {:+.1} mg",
            s.register,
            family_name(s.family),
            s.expected_g * 1e3,
            s.moved_g * 1e3
        )
    };
    steps.iter().map(step).collect::<Vec<_>>().join("; ")
}
