//! How a verification stands: trusted (its error within what its noise explains) or not, and
//! against the `--target-mg` a calibration aimed at, with why when it missed.

use serde::Serialize;

use super::Verification;
use crate::limits::TRUSTED_AFTER_NOISE_FLOOR;

/// Why a calibration missed its target by more than its noise, and what to do: an error the
/// verification resolves (not trusted), or captures too noisy for the target.
const WHY_UNTRUSTED: &str = "the calibration leaves an error the verification resolves (more than 3 noise \
    floors): the board warmed or moved between the captures and the check, or its mounting shifted; let it warm \
    up, rest it firmly and calibrate again";
const WHY_NOISY: &str = "the captures' own noise is too large for this target: rest the board on something \
    firmer and quieter, or aim at a larger --target-mg";
const WHY_SHIFTED: &str = "the captures' noise is below the target, so the error is the calibration's, within 3 \
    noise floors: the board most likely warmed between the captures and the check; let it warm up for a few \
    minutes (or keep a learned temperature model, `accelcal thermal`) and calibrate again";

/// A verification judged against the target asked for.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TargetVerdict {
    /// The | |a| - 1 g | wanted at fresh orientations, in mg (`None`: captures of a fixed length,
    /// which aim at no target).
    pub target_mg: Option<f64>,
    /// Whether the verified rms is at or below the target.
    pub reached: bool,
    /// Whether the verified rms is within what its noise floor explains (the report's "trusted").
    pub trusted: bool,
    /// Whether it missed the target by more than its noise explains: the command then fails.
    pub missed: bool,
    /// The verdict for a person, with why when the target was missed.
    pub line: String,
}

impl Verification {
    /// Whether the calibrated error is within [`TRUSTED_AFTER_NOISE_FLOOR`] noise floors.
    pub fn trusted(&self) -> bool {
        self.after_rms_mg
            <= mutant!("verdict-trusted-ten-floors", TRUSTED_AFTER_NOISE_FLOOR, 10.0)
                * self.noise_floor_mg.max(f64::EPSILON)
    }

    /// The verification against `target_mg`: reached, within its noise of it, or missed; without a
    /// target, only trusted or not.
    pub fn against(&self, target_mg: Option<f64>) -> TargetVerdict {
        let (rms, floor) = (self.after_rms_mg, self.noise_floor_mg);
        let trusted = self.trusted();
        let Some(target_mg) = target_mg else {
            let judged = if trusted { "trusted" } else { "not trusted: more than 3 noise floors" };
            let line = format!("{rms:.3} mg verified (noise floor {floor:.3} mg, {judged}); captures of a fixed length aim at no --target-mg");
            return TargetVerdict { target_mg, reached: trusted, trusted, missed: false, line };
        };
        let reached = mutant!("verdict-reached-by-the-floor", rms, rms - floor) <= target_mg;
        // NOTE: the rms carries its own noise: the error without it must exceed the target by more
        // than one noise floor for the miss to be the calibration's.
        let missed = self.after_rms_without_noise_mg > target_mg + mutant!("verdict-missed-within-noise", floor, 0.0);
        let judged = if trusted { "trusted" } else { "not trusted" };
        let head = format!("target {target_mg} mg: {rms:.3} mg verified (noise floor {floor:.3} mg, {judged})");
        let line = match (reached, missed) {
            (true, _) => format!("{head}: reached"),
            (false, false) => format!(
                "{head}: accepted: its error without the check's noise, {:.3} mg, is within one noise floor of the \
                 target, closer than this check can tell apart",
                self.after_rms_without_noise_mg
            ),
            (false, true) => format!("{head}: missed; {}", why_missed(trusted, floor > target_mg)),
        };
        TargetVerdict { target_mg: Some(target_mg), reached, trusted, missed, line }
    }
}

/// Why a target was missed: an error the verification resolves, captures whose noise alone exceeds
/// the target, or, the noise below it, an error of the calibration's own.
fn why_missed(trusted: bool, noise_above_target: bool) -> &'static str {
    match (trusted, noise_above_target) {
        (false, _) => WHY_UNTRUSTED,
        (true, true) => WHY_NOISY,
        (true, false) => WHY_SHIFTED,
    }
}

#[cfg(any(test, feature = "sim"))]
impl Verification {
    /// A verification of six orientations at this rms and noise floor, in mg, for tests.
    pub fn example(after_rms_mg: f64, noise_floor_mg: f64) -> Self {
        Verification {
            positions: 6,
            before_rms_mg: 40.0,
            after_rms_mg,
            after_max_mg: after_rms_mg * 2.0,
            after_rms_without_noise_mg: (after_rms_mg.powi(2) - noise_floor_mg.powi(2)).max(0.0).sqrt(),
            on_chip_difference_mg: 0.5,
            on_chip_noise_mg: 1.0,
            noise_floor_mg,
            before_mg: vec![],
            after_mg: vec![],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A verification of six orientations at this rms and noise floor, in mg.
    fn verified(after_rms_mg: f64, noise_floor_mg: f64) -> Verification {
        Verification::example(after_rms_mg, noise_floor_mg)
    }

    #[test]
    fn a_verification_reaches_misses_or_stays_within_its_noise_of_the_target() {
        let reached = verified(0.093, 0.05).against(Some(0.2));
        assert!(reached.reached && !reached.missed && reached.trusted, "{reached:?}");
        assert!(reached.line.ends_with("reached"), "{}", reached.line);
        // 0.26 mg with a 0.1 mg floor is 0.24 mg without it: above 0.2 mg by less than the floor.
        let near = verified(0.26, 0.1).against(Some(0.2));
        assert!(!near.reached && !near.missed, "{near:?}");
        let said = "accepted: its error without the check's noise, 0.240 mg, is within one noise floor of the target";
        assert!(near.line.contains(said), "{}", near.line);
        // The person's session over sim --pty: 0.673 mg, floor 0.190 mg (0.646 mg without it).
        let person = verified(0.673, 0.190).against(Some(0.2));
        assert!(person.missed && !person.trusted, "{person:?}");
        let noisy = verified(1.2, 0.5).against(Some(0.2));
        assert!(noisy.missed && noisy.trusted && noisy.line.contains("own noise is too large"), "{noisy:?}");
        // A resumed session over sim --pty: 0.436 mg, floor 0.187 mg (0.394 mg without it), below the
        // target: not the noise's doing.
        let shifted = verified(0.436, 0.187).against(Some(0.2));
        assert!(shifted.missed && shifted.trusted && shifted.line.contains("most likely warmed"), "{shifted:?}");
        // 1.06 mg after a 0.2 mg target with a 0.1 mg floor: missed, and not trusted.
        let missed = verified(1.06, 0.1).against(Some(0.2));
        assert!(missed.missed && !missed.trusted, "{missed:?}");
        assert!(missed.line.contains("missed; the calibration leaves an error"), "{}", missed.line);
        let fixed = verified(1.06, 0.1).against(None);
        assert!(!fixed.missed && !fixed.trusted && fixed.line.contains("aim at no --target-mg"), "{fixed:?}");
    }
}
