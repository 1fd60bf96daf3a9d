//! The thresholds of the sensor family's offset-register check (`part::offsets`, `part::check`).

/// Attempts before the check gives up on a board that keeps moving.
pub const FAMILY_CHECK_ATTEMPTS: u8 = 3;

/// How far the accelerometer's output with the offsets as found may move between the phase before and
/// the phase after the steps for the attempt to count, in g.
///
/// NOTE: a step is judged against its expected 125 mg with a margin of 25 mg (`part::check`). A still
/// board's output scatters by at most 15 mg a sample (more spoils the phase); a mean of at least
/// [`FAMILY_PHASE_MIN_SAMPLES`] is then known to 15 / sqrt(40) = 2.4 mg, a step (its phase minus the mean of the two
/// baselines) to 2.9 mg. A baseline that moved 5 mg shifts a step by at most 5 mg, which leaves
/// 20 mg, 6.9 standard deviations at the worst still scatter (a probability below 1e-11) and over 30
/// at a real part's 2-3 mg.
pub const FAMILY_BASELINE_MOVE_G: f64 = 0.005;

/// Fewest samples averaged in each phase of the family check (`part::offsets` takes 0.4 s worth
/// where that is more).
pub const FAMILY_PHASE_MIN_SAMPLES: usize = 40;

/// How far a step's effect may be from what it should be, as a fraction of the step.
///
/// NOTE: 20 % of the 125 mg step is 25 mg, far beyond what noise and a still board's drift leave
/// (see [`FAMILY_BASELINE_MOVE_G`]), and far below what a register that applies the step leaves.
pub const FAMILY_STEP_TOLERANCE: f64 = 0.2;
