//! Verification: the active calibration checked at fresh orientations, | |a| - 1 g | before and
//! after, and the chip's own corrected samples compared with it.

use std::time::Duration;

use shared::linalg;
use shared::protocol::{CalibrationSlot, CaptureStats, DeviceError, StreamKind};
use shared::Calibration;

use super::stop_rule::CaptureLength;
use super::wait::{wait_for_fresh, Rest, LIVE_WINDOW};
use super::{Feedback, Hand, ProcedureError};
use crate::limits::CAPTURE_ATTEMPTS;
use crate::link::{explain, Link, LinkError, StreamRequest, Transport};
use crate::session::Check;
pub use crate::session::Verification;
use crate::session::CHIP_SAMPLES;

/// Length of each verification capture, in seconds.
pub const VERIFY_SECONDS: u8 = 5;

/// Checks the active calibration at `positions` fresh orientations.
pub async fn verify<T: Transport>(
    link: &mut Link<T>,
    hand: &mut dyn Hand,
    positions: usize,
    wait_limit: Option<Duration>,
    feedback: &mut dyn Feedback,
) -> Result<Verification, ProcedureError> {
    verify_clear_of(link, hand, positions, wait_limit, feedback, &[]).await
}

/// [`verify`] at orientations that are also new against `calibrated`, the directions (any length)
/// the calibration was captured at: a check where the fit was made proves nothing new.
pub async fn verify_clear_of<T: Transport>(
    link: &mut Link<T>,
    hand: &mut dyn Hand,
    positions: usize,
    wait_limit: Option<Duration>,
    feedback: &mut dyn Feedback,
    calibrated: &[[f64; 3]],
) -> Result<Verification, ProcedureError> {
    let length = CaptureLength::Seconds(VERIFY_SECONDS);
    verify_with(link, hand, positions, wait_limit, feedback, calibrated, length).await
}

/// [`verify_clear_of`] with captures of `length` (an adaptive session's: as long as its target needs).
pub async fn verify_with<T: Transport>(
    link: &mut Link<T>,
    hand: &mut dyn Hand,
    positions: usize,
    wait_limit: Option<Duration>,
    feedback: &mut dyn Feedback,
    calibrated: &[[f64; 3]],
    length: CaptureLength,
) -> Result<Verification, ProcedureError> {
    let calibration = link.calibration(CalibrationSlot::Active).await?.ok_or(ProcedureError::NoActiveCalibration)?;
    hand.avoid(calibrated);
    let mut checks = Vec::with_capacity(positions);
    // NOTE: `used` holds the calibration's directions first, then each one verified.
    let mut used = calibrated.to_vec();
    for index in 0..positions {
        let check = match hand.fresh(index, feedback) {
            Ok(()) => check_fresh(link, &calibration, &mut used, wait_limit, length, feedback).await,
            Err(error) => Err(error),
        };
        let check = check.map_err(|source| stopped(source, &checks, positions))?;
        feedback.say(&format!(
            "verification {}: | |a| - 1 g | {:.2} mg raw, {:.3} mg calibrated",
            index + 1,
            check.before_mg.abs(),
            check.after_mg.abs()
        ));
        checks.push(check);
    }
    Ok(Verification::of(&checks))
}

/// A check at a fresh orientation, which only a capture that ran still uses up: after a capture the
/// board moved during, the wait for a fresh orientation starts again (the board may be anywhere now,
/// and the orientation it was brought to is still fresh).
async fn check_fresh<T: Transport>(
    link: &mut Link<T>,
    calibration: &Calibration,
    used: &mut Vec<[f64; 3]>,
    wait_limit: Option<Duration>,
    length: CaptureLength,
    feedback: &mut dyn Feedback,
) -> Result<Check, ProcedureError> {
    for _ in 0..CAPTURE_ATTEMPTS {
        let rest = Rest { limit: wait_limit, settle_seconds: length.settle_seconds(), rested_s: 0.0 };
        let direction = wait_for_fresh(link, used, rest, feedback).await?;
        match check(link, calibration, length, feedback).await {
            Err(ProcedureError::Link(LinkError::Device(error @ DeviceError::Moved { .. }))) => {
                feedback.say(&format!("{}; hold it still at a fresh orientation again", explain(&error)));
            }
            other => {
                used.push(direction);
                return other;
            }
        }
    }
    Err(ProcedureError::KeptMoving { attempts: CAPTURE_ATTEMPTS })
}

/// The error of a verification stopped part way, saying what it had measured.
fn stopped(source: ProcedureError, checks: &[Check], positions: usize) -> ProcedureError {
    let verified = match checks.len() {
        0 => format!("none of the {positions} orientations was verified"),
        n => {
            let v = Verification::of(checks);
            format!(
                "{n} of {positions} orientations verified: | |a| - 1 g | rms {:.2} mg raw, {:.3} mg calibrated (worst {:.3} mg)",
                v.before_rms_mg, v.after_rms_mg, v.after_max_mg
            )
        }
    };
    ProcedureError::VerificationStopped { source: Box::new(source), verified }
}

/// One capture at the board's orientation (not retried: [`check_fresh`] waits again), and the
/// chip's corrected samples there.
async fn check<T: Transport>(
    link: &mut Link<T>,
    calibration: &Calibration,
    length: CaptureLength,
    feedback: &mut dyn Feedback,
) -> Result<Check, ProcedureError> {
    let result = length.capture(link, feedback).await;
    feedback.progress_done();
    let (stats, _) = result?;
    // NOTE: at the capture's temperature, as the chip corrects it (a session's drift model moves o).
    let corrected = calibration.apply_at(stats.mean_g, stats.temp_c);
    let chip_mean = chip_corrected_mean(link, sample_rate_hz(&stats)).await?;
    Ok(Check {
        before_mg: (f64::from(linalg::norm(stats.mean_g)) - 1.0) * 1000.0,
        after_mg: (f64::from(linalg::norm(corrected)) - 1.0) * 1000.0,
        noise_mg: norm_noise_g(calibration, &stats, corrected) * 1000.0,
        on_chip_mg: f64::from(linalg::norm(linalg::sub(chip_mean, corrected))) * 1000.0,
        on_chip_noise_mg: mean_noise_g(calibration, &stats, CHIP_SAMPLES) * 1000.0,
    })
}

/// The standard deviation of |a| of a capture's mean, in g: d^T M diag(std^2 / n) M^T d with d the
/// direction of a.
///
/// NOTE: samples taken as independent, as the simulated sensor's white noise is; a real sensor's
/// low-pass filter correlates neighbours, which this floor would understate.
fn norm_noise_g(calibration: &Calibration, stats: &CaptureStats, corrected: [f32; 3]) -> f64 {
    let direction = linalg::scale(corrected, 1.0 / linalg::norm(corrected).max(f32::MIN_POSITIVE));
    let along = linalg::mul_vec(&linalg::transpose(&calibration.matrix), direction);
    let samples = f64::from(stats.samples.max(1));
    let variance: f64 = (0..3).map(|k| f64::from(along[k] * stats.std_g[k]).powi(2) / samples).sum();
    variance.sqrt()
}

/// The size of the noise of a mean of `samples` corrected samples, in g: sqrt(trace(M diag(std^2) M^T) / n).
fn mean_noise_g(calibration: &Calibration, stats: &CaptureStats, samples: u32) -> f64 {
    let m = &calibration.matrix;
    let variance: f64 =
        (0..3).flat_map(|i| (0..3).map(move |j| f64::from(m[i][j] * stats.std_g[j]).powi(2))).sum::<f64>();
    (variance / f64::from(samples.max(1))).sqrt()
}

/// The sensor's sample rate a capture ran at, in Hz (the chip counts its seconds as samples / rate);
/// the live window's for a capture without samples.
fn sample_rate_hz(stats: &CaptureStats) -> u16 {
    let rate = (stats.samples as f32 / stats.seconds).round();
    if stats.samples > 0 && rate.is_finite() && (1.0..=f32::from(u16::MAX)).contains(&rate) {
        rate as u16
    } else {
        LIVE_WINDOW.rate_hz
    }
}

/// Mean of samples corrected by the chip itself, streamed at the sensor's rate.
// NOTE: at the sensor's rate rather than the live window's 20 Hz, the 20 samples take a fifth of a
// second of the person's time instead of a whole one, for the same noise.
async fn chip_corrected_mean<T: Transport>(link: &mut Link<T>, rate_hz: u16) -> Result<[f32; 3], ProcedureError> {
    let request = StreamRequest { kind: StreamKind::Calibrated, rate_hz, count: CHIP_SAMPLES };
    let (mut sum, mut count) = ([0.0f32; 3], 0u32);
    link.stream(request, |sample| {
        sum = linalg::add(sum, sample.accel_g);
        count += 1;
    })
    .await?;
    Ok(linalg::scale(sum, 1.0 / count.max(1) as f32))
}

#[cfg(test)]
mod tests {
    use super::*;
    use shared::AccelRange;

    fn capture(mean_g: [f32; 3], std_g: [f32; 3], samples: u32) -> CaptureStats {
        let (gyro_mean_dps, gyro_std_dps) = ([0.0; 3], [0.0; 3]);
        let (seconds, temp_c, clipped, range) = (5.0, 25.0, 0, AccelRange::G2);
        CaptureStats { samples, seconds, mean_g, std_g, gyro_mean_dps, gyro_std_dps, temp_c, clipped, range }
    }

    #[test]
    fn the_chip_s_samples_stream_at_the_rate_the_capture_ran_at() {
        let stats = |samples, seconds| CaptureStats { seconds, ..capture([0.0, 0.0, 1.0], [0.003; 3], samples) };
        assert_eq!(sample_rate_hz(&stats(213, 2.13)), 100);
        assert_eq!(sample_rate_hz(&stats(1000, 1.0)), 1000);
        assert_eq!(sample_rate_hz(&stats(0, 0.0)), LIVE_WINDOW.rate_hz, "no samples, no rate: the live window's");
    }

    #[test]
    fn the_noise_of_the_norm_is_the_scatter_along_gravity_over_root_n() {
        // z up: only z's scatter moves |m|; 400 samples divide it by 20.
        let z_up = capture([0.0, 0.0, 1.0], [0.009, 0.009, 0.003], 400);
        let noise = |stats: &CaptureStats| norm_noise_g(&Calibration::identity(AccelRange::G2), stats, stats.mean_g);
        assert!((noise(&z_up) - 0.003 / 20.0).abs() < 1e-9);
        // Tilted half-way between x and y: each contributes half its variance.
        let r = std::f32::consts::FRAC_1_SQRT_2;
        let tilted = capture([r, r, 0.0], [0.004, 0.002, 0.05], 100);
        let expected = ((0.5 * 0.004f64.powi(2) + 0.5 * 0.002f64.powi(2)) / 100.0).sqrt();
        assert!((noise(&tilted) - expected).abs() < 1e-8, "{} vs {expected}", noise(&tilted));
    }

    #[test]
    fn the_chip_is_judged_against_the_noise_of_its_own_twenty_sample_mean() {
        // 3 mg per axis over 20 samples: sqrt(3) * 3 / sqrt(20) = 1.16 mg of noise in the mean.
        let stats = capture([0.0, 0.0, 1.0], [0.003; 3], 500);
        let noise_mg = mean_noise_g(&Calibration::identity(AccelRange::G2), &stats, CHIP_SAMPLES) * 1000.0;
        assert!((noise_mg - 1.162).abs() < 0.001, "{noise_mg}");
        let verification = |difference| Verification {
            on_chip_difference_mg: difference,
            on_chip_noise_mg: noise_mg,
            ..Verification::of(&[])
        };
        assert!(verification(1.35)
            .chip_agreement()
            .starts_with("chip and host agree: they differ by 1.35 mg, within 3 times the 1.16 mg noise"));
        assert!(verification(5.0).chip_agreement().contains("does not apply the calibration verified"));
    }

    #[test]
    fn the_worst_error_counts_readings_below_1_g_as_well_as_above() {
        // |a| of 0.9988 g is 1.2 mg short: the worst error is 1.2 mg, not the 0.5 mg above 1 g.
        let check =
            |before_mg, after_mg| Check { before_mg, after_mg, noise_mg: 0.1, on_chip_mg: 0.01, on_chip_noise_mg: 1.0 };
        let result = Verification::of(&[check(3.0, 0.3), check(-4.0, -1.2), check(2.0, 0.5)]);
        assert_eq!(result.after_max_mg, 1.2);
        // sqrt((0.09 + 1.44 + 0.25) / 3) = 0.770 mg
        assert!((result.after_rms_mg - 0.770_281).abs() < 1e-6, "{}", result.after_rms_mg);
        assert_eq!(result.positions, 3);
    }
}
