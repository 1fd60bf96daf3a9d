//! The host's thresholds, in one table, each with the reason for its value. Messages quote these
//! constants; nothing else restates them. The plausibility limits of a calibration are the system's
//! one table in `shared` ([`calibration`]), which the chip applies too.
//!
//! One table in parts, all read as `limits::NAME`: this file (readings, orientations, verification,
//! statistics), [`procedure`] (a session's captures), [`fits`] (when a fit is made at all),
//! [`stream`] (a foreign sketch's stream), [`link`] (the port and the lot database) and [`part`]
//! (the sensor family's offset-register check).

pub use shared::calibration::limits as calibration;

pub mod fits;
pub mod link;
pub mod part;
pub mod procedure;
pub mod stream;

pub use fits::*;
pub use link::*;
pub use part::*;
pub use procedure::*;
pub use stream::*;

/// Largest accelerometer scatter (standard deviation on any axis), in g, of a board that counts as
/// still.
///
/// NOTE: the device's own capture check (`shared::protocol::MAX_STILL_ACCEL_STD_G`): the live
/// check before a capture accepts exactly what the capture will accept, so a capture started on a
/// still board is not refused for moving.
pub const STILL_ACCEL_STD_G: f64 = shared::protocol::MAX_STILL_ACCEL_STD_G as f64;

/// Largest difference, in g, between |m| at rest and 1 g for a reading to count as any position.
///
/// NOTE: the system's one plausibility limit (`shared::protocol::MAX_GRAVITY_ERROR_G`, whose note
/// gives the reason): the chip's face detection and the host's live wait refuse the same readings.
pub const MAX_GRAVITY_ERROR_G: f64 = shared::protocol::MAX_GRAVITY_ERROR_G as f64;

/// Below this |m|, in g, the sensor is taken to return zeros rather than a wrong reading.
///
/// NOTE: a sleeping MPU-6050 holds its data registers at zero, and a chip that is not an MPU-6050
/// answers zeros or a constant near it; any working sensor reads several hundred mg at least.
pub const ZERO_READING_G: f64 = 0.05;

/// Largest tilt, in degrees, of a reading from a face for it to count as that face: while the
/// procedure waits for a face, and when a fit detects the faces in a data file.
///
/// NOTE: the system's face tolerance (`shared::orientation::DEFAULT_FACE_TOLERANCE_DEG`, whose note
/// gives the reason: the zero-g offset alone tilts a reading by up to 8.5 degrees).
pub const FACE_TOLERANCE_DEG: f64 = shared::orientation::DEFAULT_FACE_TOLERANCE_DEG as f64;

/// Largest tilt, in degrees, from a corner (three axes equally up) for the board to count as there.
///
/// NOTE: a corner lies 54.7 degrees from each of its three faces: with the face tolerance this
/// keeps the regions apart (20 + 20 < 54.7), so no reading counts as both a face and a corner.
pub const CORNER_TOLERANCE_DEG: f64 = 20.0;

/// Tilt, in degrees, within which a *given* reference counts as exactly one of the six faces.
///
/// NOTE: a reference is a known direction, not a measurement; only rounding in a file moves it.
pub const REFERENCE_FACE_TOLERANCE_DEG: f64 = 0.5;

/// Smallest angle, in degrees, between two verification orientations.
///
/// NOTE: a hand resting the board "in the same place" again lands within a few degrees of it;
/// 20 degrees is well clear of that, so two verifications this far apart are two orientations.
pub const FRESH_DEG: f64 = 20.0;

/// Smallest component of a reading, relative to |m|, for it to count as pointing an axis up or
/// down when the orientation-free fits check the spread of the positions.
///
/// NOTE: cos 72.5 degrees: a position within 72.5 degrees of an axis constrains that axis's scale
/// and offset usefully; beyond it the axis reads less than 0.3 g and barely moves.
pub const AXIS_SPREAD: f64 = 0.3;

/// Smallest angle, in degrees, between two known orientations for them to count as independent.
///
/// NOTE: `reference-norm12` needs two directions to fix the rotation; two references closer than
/// this are one direction held twice.
pub const INDEPENDENT_REFERENCES_DEG: f64 = 10.0;

/// Largest calibrated verification error, as a multiple of the verification's noise floor, for a
/// report to call the calibration trusted.
///
/// NOTE: with Gaussian noise the RMS over a few orientations stays below 3 noise floors with
/// near certainty; more than that is an error the calibration left that the verification resolves.
pub const TRUSTED_AFTER_NOISE_FLOOR: f64 = 3.0;

/// Fewest samples a row must average for its own standard deviation to be trusted.
///
/// NOTE: a standard deviation from n samples is uncertain by 1 / sqrt(2 (n - 1)): 24 % at 10
/// samples, 100 % at 2. Below 10 a row's spread says little about the noise.
pub const TRUSTED_SAMPLE_COUNT: u32 = 10;

/// Residual | |a| - g |, in mg RMS, below which no real static model is expected to go.
///
/// NOTE: the MPU-6050's zero-g offset drifts with temperature by about 0.5 mg/degC (datasheet: +-35 mg
/// over 0-70 degC); a degree or two of warming over a calibration run moves the readings by 0.5-1 mg
/// that no static 12-parameter model can follow. Residuals below this are as good as a model gets.
pub const MODEL_FLOOR_MG: f64 = 1.0;

/// A row whose sample spread exceeds the pooled spread of all rows by this factor on some axis was
/// taken on a board that moved.
///
/// NOTE: a still capture's spread is the sensor's noise, the same in every row to within the
/// uncertainty of a standard deviation (24 % at 10 samples); three times it is motion.
pub const MOVED_STD_RATIO: f64 = 3.0;

/// RMS angle, in degrees, between corrected readings and known orientations above which the known
/// orientations count as placed off.
///
/// NOTE: a calibrated MPU-6050 points to within about 0.1 degree (1.7 mg of cross-axis error); half a
/// degree is a placement error, not the sensor.
pub const PLACEMENT_DEG: f64 = 0.5;

/// [`AXIS_SPREAD`] as the largest angle from an axis, in whole degrees, for messages.
pub fn axis_spread_deg() -> f64 {
    AXIS_SPREAD.acos().to_degrees().round()
}

/// Smallest temperature span a temperature model is learned from, in degC: over less, the drift of
/// 1-2 mg/degC is hardly above the bias wander and a polynomial extrapolates wildly.
pub const MIN_THERMAL_SPAN_C: f64 = 10.0;
/// A learning run counts as stalled when the temperature moved less than this over
/// [`THERMAL_STALL_ROUNDS`] rounds, in degC: the die has settled where it is.
pub const THERMAL_STALL_C: f64 = 0.3;
/// Rounds of captures over which a stall is judged.
pub const THERMAL_STALL_ROUNDS: usize = 10;

/// Gyro rate, in deg/s away from the bias at the pose before, above which a recorded move has begun.
///
/// NOTE: a hand's turn between positions runs at tens to hundreds of deg/s; a board resting in a
/// hand trembles at about a deg/s; the rate noise at 100 Hz is 0.035 deg/s (sim::physics).
pub const MOVE_STARTED_DPS: f64 = 10.0;
/// Gyro rate, in deg/s away from the bias at the pose before, below which the board counts as still
/// again at the end of a move (the end of a turn drifts a little as the hand lets go).
pub const MOVE_STILL_DPS: f64 = 3.0;
/// Change of the accelerometer's direction, in degrees, that counts as a move even when the gyro saw
/// no turn (then the move is dropped, not waited for).
///
/// NOTE: ten times the direction noise of one raw sample at 100 Hz (2.8 mg, 0.16 degrees), and far
/// below the tolerance of any wanted orientation.
pub const MOVE_TILTED_DEG: f64 = 5.0;
/// Still time, in seconds, that ends a recorded move: long enough that the turn has ended, short
/// enough not to lengthen the session (the wait for the next position asks for 2 s more).
pub const MOVE_STILL_SECONDS: f64 = 0.5;
/// Longest move recorded, in seconds: a person reads the instruction and turns the board.
pub const MAX_MOVE_SECONDS: u32 = 30;
/// Largest angle, in degrees, between where a move ended and where the next capture was taken: the
/// board was moved again after the recording ended, so the turn does not reach that pose.
///
/// NOTE: the accelerometer's direction over half a second of samples is good to 0.03 degrees; a
/// tenth of a degree is already a 0.1 % scale error on a 90 degree turn.
pub const MOVED_AFTER_TURN_DEG: f64 = 0.2;
/// A raw gyro sample within this fraction of the full-scale range counts as clipped.
///
/// NOTE: the largest count, 32767 at 32.8 LSB per deg/s, reads 999.0 deg/s of a 1000 deg/s range.
pub const GYRO_CLIPPED_FRACTION: f64 = 0.995;
/// Rest, in seconds, streamed before and after the gyro's verification turn: the accelerometer's
/// angle between the two rests is the reference (400 ug noise per sample at 100 Hz averages to
/// 0.02 degrees over a second at each end).
pub const TURN_CHECK_REST_SECONDS: f64 = 1.0;
/// Quarter turns asked for before the gyro's verification is given up: a person who turned about
/// the vertical, or did not rest, is told why and asked again; a third miss says more of the same
/// would not help (each turn takes a few seconds).
pub const TURN_CHECK_ATTEMPTS: usize = 3;

/// Most fresh orientations a verification asks for.
///
/// NOTE: each must be 20 degrees from the calibration's 14 positions and from the others, and the
/// simulated hand keeps 30 degrees: measured, `calibrate --sim --chip-fit --verify 20` waited 64 s and
/// failed (seed 1) while 16 and 17 passed in 2 s (16 on seeds 1-7); a person would not turn the board
/// more often than that anyway.
pub const MAX_VERIFY_POSITIONS: i64 = 16;

/// Most boards calibrated together on one fixture.
/// NOTE: a fixture a hand turns holds a few dozen boards at most; each board is a thread and a
/// port (a simulated one: a thread more), and 64 keeps that within any machine's limits.
pub const MAX_BOARDS: i64 = 64;

/// Largest placement error of the simulated hand, in degrees.
///
/// NOTE: beyond this a face is no longer reliably within the face tolerance's reach after the
/// sensor's own offset tilts it, and the run would wait for a face it never reaches: measured,
/// `calibrate --sim --sim-placement-deg 10` waited 60 s and failed (seed 1), 9 passed, 8 on seeds 1-7.
pub const MAX_PLACEMENT_DEG: f64 = 8.0;

/// Largest thermal learning target, in degC.
///
/// NOTE: the MPU-6050 works from -40 to +85 degC (Product Specification 6.1); no board warms from
/// one end to the other while it is being learned, and a larger target could never be reached.
pub const MAX_THERMAL_SPAN_C: f64 = 100.0;

/// Below this ratio of smallest to largest singular value the parameters are not observable.
/// NOTE: the ratio comes from eigenvalues of J^T J, whose rounding floor is 1e-16 relative: 1e-7 in
/// singular values stays clear of it.
pub const UNOBSERVABLE_RATIO: f64 = 1e-7;

/// Below this ratio the condition number is worth a warning.
pub const POORLY_CONDITIONED_RATIO: f64 = 1e-3;

/// Below this probability the residuals are judged larger than the noise explains.
pub const NOISE_TEST_LEVEL: f64 = 1e-3;

/// Below this probability of a chi-square at least as large under noise alone, the residuals are
/// taken to hold more than noise and the noise-based errors are scaled up by sqrt(chi-square / dof).
///
/// NOTE: 5 %: 95 % of honest fits keep the noise's error unscaled (scaling every fit whose chi-square
/// exceeds its dof would inflate honest errors on average), while a misfit the residuals show is
/// carried into the errors.
pub const SCATTER_SIGNIFICANCE: f64 = 0.05;

/// Above this leverage (the largest eigenvalue of the row's hat-matrix block) a row carries most of
/// some parameter: the one-step change is least trustworthy there, so the row is refitted instead.
/// NOTE: the leverages add up to the parameter count, so at most twice that many rows exceed 0.5.
pub const HIGH_LEVERAGE: f64 = 0.5;

/// Inclination beyond which toolface is undefined (the x-y projection vanishes), in degrees.
/// NOTE: at 89 degrees the x-y projection is sin(1 degree) = 1.7 % of g: 1 mg of error there
/// already turns the toolface by 3.3 degrees.
pub const TOOLFACE_UNDEFINED_ABOVE_DEG: f64 = 89.0;

/// Share of the Allan variance at its minimum the flicker floor must hold for B to count as resolved.
/// NOTE: below half, the minimum is mostly where the white noise and the random walk meet, and a
/// B read there is their sum rather than a flicker floor.
pub const RESOLVED_FLICKER_SHARE: f64 = 0.5;

/// Share of the Allan variance at the longest averaging time the random walk must hold to count as
/// resolved. NOTE: below half, the curve's end is still mostly white noise or flicker, and a K read
/// there is what the fit left (often zero), which would tell Kalibr the bias never moves.
pub const RESOLVED_RANDOM_WALK_SHARE: f64 = 0.5;

/// How far a given rate may be from the one a file's time stamps show, as a fraction.
// NOTE: time stamps are printed to the microsecond; at 100 Hz that is 1e-4 of a sample interval.
pub const RATE_AGREEMENT: f64 = 0.01;

/// How far, as a fraction, a board's sample rate may be from a session's for it to be resumed.
/// NOTE: a rate the board achieves a little differently (99 Hz for 100) measures the same; a board
/// left at 1000 Hz by `record` filters and averages otherwise.
pub const RESUME_RATE_TOLERANCE: f64 = 0.05;

/// How many times its own noise the chip may differ from the host before it is said to apply
/// something else (a 3-sigma bound on each axis of the difference).
pub const CHIP_AGREEMENT_SIGMAS: f64 = 3.0;

/// Largest angle, in degrees, between the check turn's axis and the horizontal: the accelerometer
/// sees a turn about a tilted line as a smaller tilt, and a scale error of the gyro less and less.
// NOTE: a turn over an edge of a board resting on a table is about a horizontal line; 20 degrees
// leaves a hand's turn in the air room while the tilt still shows 94 % of the turn's angle.
pub const MAX_CHECK_AXIS_ELEVATION_DEG: f64 = 20.0;

/// A board whose last few samples scatter more than this, in g, is moving.
/// NOTE: about eight times the MPU-6050's noise at full bandwidth (400 ug/sqrt(Hz) over 260 Hz:
/// 6.5 mg rms, Product Specification 6.2): only motion reaches it.
pub const MOVING_SCATTER_G: f64 = 0.05;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_face_and_corner_regions_do_not_overlap() {
        let corner_to_face_deg = (1.0 / 3f64.sqrt()).acos().to_degrees();
        assert!((corner_to_face_deg - 54.7356).abs() < 1e-3);
        assert!(FACE_TOLERANCE_DEG + CORNER_TOLERANCE_DEG < corner_to_face_deg);
    }
}
