//! The family confirmed by what its offset registers do, judged against the family the board runs the
//! part as (found by register read-back at boot) and the family its WHO_AM_I claims.

use serde::Serialize;
use shared::part::{Family, Part};
use shared::protocol::{SensorConfig, SensorIdentity};

use super::family_name;
use super::offsets::{measure, Measured, OffsetCheckError, OffsetStep};
use crate::limits::FAMILY_STEP_TOLERANCE;
use crate::link::{Client, Port};

/// What a step did to the x output.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StepResponse {
    /// Moved by the step, within [`FAMILY_STEP_TOLERANCE`].
    AsExpected,
    /// Stayed within [`FAMILY_STEP_TOLERANCE`] of the step of where it was.
    NotMoved,
    /// Moved, but by another amount.
    Unexpected,
}

impl OffsetStep {
    /// What the step did.
    pub fn response(&self) -> StepResponse {
        let margin = FAMILY_STEP_TOLERANCE * self.expected_g.abs();
        if (self.moved_g - self.expected_g).abs() < margin {
            StepResponse::AsExpected
        } else if self.moved_g.abs() < margin {
            StepResponse::NotMoved
        } else {
            StepResponse::Unexpected
        }
    }
}

/// The check's verdict.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    /// The offset registers are the family's the board runs the part as, the one its WHO_AM_I claims
    /// (or an unknown part's, which claims none).
    Confirmed,
    /// The offset registers confirm the family the board runs the part as, which is not the one its
    /// WHO_AM_I claims.
    ContradictsWhoAmI { claimed: Family },
    /// The offset registers are the other family's than the register read-back found.
    ContradictsReadBack { by_offsets: Family },
    /// Neither family's offset register moved the output.
    OffsetsIgnored,
    /// Both moved it, or one by another amount than its map says.
    Unclear,
    /// The board moved during every attempt.
    BoardMoved,
}

/// The family check of one sensor.
#[derive(Debug, Clone, PartialEq)]
pub struct FamilyCheck {
    /// The family the board runs the part as.
    pub family: Family,
    /// The part its WHO_AM_I names.
    pub part: Part,
    /// Each family's step (empty when the board kept moving).
    pub steps: Vec<OffsetStep>,
    /// Attempts it took.
    pub attempts: u8,
    /// Why the last attempt counted as moved, when the board kept moving.
    pub moved: Option<String>,
    pub verdict: Verdict,
}

/// Steps the offset registers of the sensor `identity`, on a board configured as `config`, and judges
/// its family; every register is restored, and the temperature bins the check's samples went into
/// are emptied (a stepped output is no measure of the sensor's drift with temperature).
pub fn check_family<P: Port>(
    client: &mut Client<P>,
    identity: &SensorIdentity,
    config: SensorConfig,
) -> Result<FamilyCheck, OffsetCheckError> {
    let measured = measure(client, config)?;
    client.take_temperature_bins()?;
    Ok(FamilyCheck::judge(identity, measured))
}

impl FamilyCheck {
    /// The verdict on what the measurement found.
    pub fn judge(identity: &SensorIdentity, measured: Measured) -> Self {
        let (family, part) = (identity.family, identity.identification().part);
        let (steps, attempts, moved) = match measured {
            Measured::Steps { steps, attempts } => (steps.to_vec(), attempts, None),
            Measured::KeptMoving { attempts, why } => (Vec::new(), attempts, Some(why)),
        };
        let verdict = if moved.is_some() { Verdict::BoardMoved } else { verdict(&steps, family, part) };
        FamilyCheck { family, part, steps, attempts, moved, verdict }
    }

    /// Whether the offset registers confirm the family the board runs the part as.
    pub fn confirmed(&self) -> bool {
        mutant!(
            "family-lookalike-unconfirmed",
            matches!(self.verdict, Verdict::Confirmed | Verdict::ContradictsWhoAmI { .. }),
            matches!(self.verdict, Verdict::Confirmed)
        )
    }

    /// What confirmed the family ("offset registers"), or `None` when nothing did.
    pub fn confirmed_by(&self) -> Option<&'static str> {
        self.confirmed().then_some("offset registers")
    }
}

/// The verdict on two steps, in [`super::offsets::FAMILIES`] order.
fn verdict(steps: &[OffsetStep], family: Family, part: Part) -> Verdict {
    let responses: Vec<StepResponse> = steps.iter().map(OffsetStep::response).collect();
    let by_offsets = match responses[..] {
        [StepResponse::AsExpected, StepResponse::NotMoved] => steps[0].family,
        [StepResponse::NotMoved, StepResponse::AsExpected] => steps[1].family,
        [StepResponse::NotMoved, StepResponse::NotMoved] => return Verdict::OffsetsIgnored,
        _ => return Verdict::Unclear,
    };
    match part.claimed_family() {
        _ if by_offsets != family => Verdict::ContradictsReadBack { by_offsets },
        Some(claimed) if claimed != by_offsets => Verdict::ContradictsWhoAmI { claimed },
        _ => Verdict::Confirmed,
    }
}

/// What `info --json` and `selftest --json` print as `family_check`.
#[derive(Debug, Clone, Serialize)]
pub struct FamilyCheckJson {
    /// `confirmed`, `contradicts_who_am_i`, `contradicts_read_back`, `offsets_ignored`, `unclear` or
    /// `board_moved`.
    pub verdict: &'static str,
    /// Whether the offset registers confirm the family the board runs the part as.
    pub confirmed: bool,
    /// The family the board runs the part as.
    pub family: &'static str,
    /// One per family's x offset register stepped (none when the board kept moving).
    pub steps: Vec<StepJson>,
    pub attempts: u8,
    /// The check in words, as `info` prints it.
    pub summary: String,
}

/// One register stepped.
#[derive(Debug, Clone, Serialize)]
pub struct StepJson {
    /// The family whose register it is.
    pub family: &'static str,
    pub register: u8,
    /// Whether the register kept the value written.
    pub kept: bool,
    /// What the step should add to the x output, and what it did, in mg.
    pub expected_mg: f64,
    pub moved_mg: f64,
    /// `as_expected`, `not_moved` or `unexpected`.
    pub response: &'static str,
}

impl FamilyCheckJson {
    /// The JSON form of a check.
    pub fn of(check: &FamilyCheck) -> Self {
        FamilyCheckJson {
            verdict: verdict_name(check.verdict),
            confirmed: check.confirmed(),
            family: family_name(check.family),
            steps: check.steps.iter().map(StepJson::of).collect(),
            attempts: check.attempts,
            summary: check.summary(),
        }
    }
}

impl StepJson {
    fn of(step: &OffsetStep) -> Self {
        let response = match step.response() {
            StepResponse::AsExpected => "as_expected",
            StepResponse::NotMoved => "not_moved",
            StepResponse::Unexpected => "unexpected",
        };
        let mg = |g: f64| (g * 1e4).round() / 10.0;
        StepJson {
            family: family_name(step.family),
            register: step.register,
            kept: step.kept,
            expected_mg: mg(step.expected_g),
            moved_mg: mg(step.moved_g),
            response,
        }
    }
}

fn verdict_name(verdict: Verdict) -> &'static str {
    match verdict {
        Verdict::Confirmed => "confirmed",
        Verdict::ContradictsWhoAmI { .. } => "contradicts_who_am_i",
        Verdict::ContradictsReadBack { .. } => "contradicts_read_back",
        Verdict::OffsetsIgnored => "offsets_ignored",
        Verdict::Unclear => "unclear",
        Verdict::BoardMoved => "board_moved",
    }
}

#[cfg(test)]
mod tests;
