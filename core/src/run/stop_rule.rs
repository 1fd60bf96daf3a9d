//! How long a position is averaged: until its mean is known well enough for the calibration's
//! target accuracy. The board judges that itself from the scatter of the capture so far
//! ([`CaptureGoal`]); with a noise report (`accelcal noise --json`) the host fixes the length instead.

use std::path::Path;

use shared::protocol::{CaptureGoal, CaptureStats, MIN_GOAL_SAMPLES};
use shared::Position;

use super::{Feedback, ProcedureError};
use crate::limits::{GOAL_SETTLE_SECONDS, MAX_CAPTURE_SECONDS, MIN_CAPTURE_SECONDS, SETTLE_SECONDS};
use crate::link::{Link, LinkError, Transport};

/// Captures a default session plans for, for the share of the target each mean gets: its fourteen
/// positions and the first one again (it stops sooner once the fit predicts the target: on the
/// simulated sensor after thirteen).
pub const PLANNED_CAPTURES: f64 = 15.0;
/// Parameters fitted to them: the nine of the orientation-free fit and an offset drift per axis.
const FITTED_PARAMETERS: f64 = 12.0;

/// How long one capture runs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CaptureLength {
    /// A fixed number of seconds (5-20, the classic request).
    Seconds(u8),
    /// Until the board's stop rule ends it.
    Goal(CaptureGoal),
}

impl CaptureLength {
    /// Runs the capture, showing its progress.
    pub(super) async fn capture<T: Transport>(
        self,
        link: &mut Link<T>,
        feedback: &mut dyn Feedback,
    ) -> Result<(CaptureStats, Option<Position>), LinkError> {
        let mut progress = |p: &shared::protocol::CaptureProgress| feedback.progress(p.samples, p.total_samples);
        match self {
            CaptureLength::Seconds(seconds) => link.capture(seconds, &mut progress).await,
            CaptureLength::Goal(goal) => link.capture_until(goal, &mut progress).await,
        }
    }

    /// How long the board must rest where it should before this capture starts, in seconds.
    pub fn settle_seconds(self) -> f64 {
        match self {
            CaptureLength::Seconds(_) => SETTLE_SECONDS,
            CaptureLength::Goal(_) => GOAL_SETTLE_SECONDS,
        }
    }
}

/// Where the noise that sets the capture length comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum Noise {
    /// The scatter the board measures during each capture.
    Measured,
    /// A noise report: the white noise of each accelerometer axis (Allan N, g/sqrt(Hz): a mean over
    /// T seconds errs by N / sqrt(T)) and the averaging time beyond which longer stops helping.
    Report { white_noise_g: [f64; 3], capture_limit_s: Option<f64> },
}

/// The rule each position's capture stops by.
#[derive(Debug, Clone, PartialEq)]
pub struct StopRule {
    /// The wanted | |a| - g | error at a fresh orientation, in mg.
    pub target_mg: f64,
    /// Where the noise comes from.
    pub noise: Noise,
    /// The sensor's sample rate, in Hz.
    pub rate_hz: u16,
}

impl StopRule {
    /// The standard error each axis' mean must reach, in g: a least-squares fit of p parameters
    /// from n equally good captures predicts at a fresh orientation about sigma sqrt(p / n).
    pub fn mean_std_g(&self) -> f64 {
        self.target_mg * 1e-3 * (PLANNED_CAPTURES / FITTED_PARAMETERS).sqrt()
    }

    /// The request for one capture.
    pub fn goal(&self) -> CaptureGoal {
        self.goal_for(self.mean_std_g())
    }

    /// The request for one verification capture: its mean known to the target itself, so that the
    /// check's noise floor (the RMS of that noise over its orientations) is the target, which the
    /// verification then takes out of its figure (`after_rms_without_noise_mg`).
    // NOTE: half the target, as before, made each check four times as long (about 8 s of averaging
    // instead of 2, three times over, in a session of one minute).
    pub fn verification_goal(&self) -> CaptureGoal {
        self.goal_for(self.target_mg * 1e-3)
    }

    /// The request for a capture whose mean each axis must know to `mean_std_g`.
    fn goal_for(&self, mean_std_g: f64) -> CaptureGoal {
        let samples = |seconds: f64| ((seconds * f64::from(self.rate_hz)).round() as u32).max(MIN_GOAL_SAMPLES);
        let (min_samples, max_samples) = match &self.noise {
            Noise::Measured => (samples(MIN_CAPTURE_SECONDS), samples(MAX_CAPTURE_SECONDS)),
            Noise::Report { .. } => {
                let fixed = samples(self.report_seconds(mean_std_g));
                (fixed, fixed)
            }
        };
        CaptureGoal { mean_std_g: mean_std_g as f32, min_samples, max_samples }
    }

    /// The capture length a noise report asks for: the worst axis' (N / sigma)^2, within the limits
    /// and no longer than the report's useful averaging time.
    fn report_seconds(&self, mean_std_g: f64) -> f64 {
        let Noise::Report { white_noise_g, capture_limit_s } = &self.noise else {
            return MAX_CAPTURE_SECONDS;
        };
        let worst = white_noise_g.iter().copied().fold(0.0, f64::max);
        let limit_s = capture_limit_s.unwrap_or(MAX_CAPTURE_SECONDS);
        let longest = mutant!(
            "stop-rule-no-upper-clamp",
            mutant!(
                "stop-rule-no-lower-clamp",
                limit_s.clamp(MIN_CAPTURE_SECONDS, MAX_CAPTURE_SECONDS),
                limit_s.max(MIN_CAPTURE_SECONDS)
            ),
            limit_s
        );
        (worst / mean_std_g).powi(2).clamp(MIN_CAPTURE_SECONDS, longest)
    }

    /// Why a capture stopped when it did, in words.
    pub fn why_stopped(&self, stats: &CaptureStats) -> String {
        let known_mg = 1e3 * stats.std_g.iter().copied().fold(0.0, f32::max) / (stats.samples.max(1) as f32).sqrt();
        let goal_mg = self.mean_std_g() * 1e3;
        let seconds = stats.seconds;
        match &self.noise {
            Noise::Report { .. } => {
                format!("{seconds:.1} s, as the noise report asks for a mean known to {goal_mg:.3} mg")
            }
            Noise::Measured if stats.samples < self.goal().max_samples => {
                format!("{seconds:.1} s: its mean is known to {known_mg:.3} mg ({goal_mg:.3} mg wanted)")
            }
            Noise::Measured => format!(
                "{seconds:.1} s, the longest capture: its mean is known to {known_mg:.3} mg ({goal_mg:.3} mg wanted)"
            ),
        }
    }
}

/// The accelerometer's noise from an `accelcal noise --json` report: white noise per axis (ug/sqrt(Hz)
/// there, one-sided as datasheets give it) and the capture limit; `text` is the report read from `path`.
pub fn noise_from_report(path: &Path, text: &str) -> Result<Noise, ProcedureError> {
    let unreadable = |reason: String| ProcedureError::NoiseReport { path: path.to_owned(), reason };
    let report = crate::noise::json::read(text).map_err(unreadable)?;
    let mut white_noise_g = [0.0; 3];
    for (axis, name) in ["accel_x", "accel_y", "accel_z"].iter().enumerate() {
        let density = report.axis(name).ok().and_then(|a| a.white_noise_density).filter(|d| *d > 0.0 && d.is_finite());
        let density = density.ok_or_else(|| unreadable(format!("it has no {name}.white_noise_density")))?;
        // NOTE: the report's density is one-sided (noise/fit.rs); a mean errs by the two-sided N / sqrt(T).
        white_noise_g[axis] = density * 1e-6 / std::f64::consts::SQRT_2;
    }
    // NOTE: a limit that is only a lower bound (the deviation still fell at the longest averaging
    // time the recording allowed) caps nothing.
    let advice = &report.calibration;
    let capture_limit_s = advice.capture_limit_s.filter(|_| !advice.capture_limit_is_lower_bound);
    Ok(Noise::Report { white_noise_g, capture_limit_s })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rule(noise: Noise) -> StopRule {
        StopRule { target_mg: 0.2, noise, rate_hz: 100 }
    }

    #[test]
    fn each_mean_gets_its_share_of_the_target_and_the_board_judges_it() {
        // 0.2 mg over sqrt(12 / 15): 0.2236 mg per axis; 0.5 s to 8 s at 100 Hz.
        let goal = rule(Noise::Measured).goal();
        assert!((goal.mean_std_g - 0.2236e-3).abs() < 1e-7, "{goal:?}");
        assert_eq!((goal.min_samples, goal.max_samples), (50, 800));
        assert!((rule(Noise::Measured).verification_goal().mean_std_g - 0.2e-3).abs() < 1e-9);
        // Such a capture guards its own start; a fixed one waits for the person.
        assert_eq!(CaptureLength::Goal(goal).settle_seconds(), 0.5);
        assert_eq!(CaptureLength::Seconds(5).settle_seconds(), 2.0);
    }

    #[test]
    fn a_noise_report_fixes_the_length_within_its_useful_averaging_time() {
        // Allan N of 283 ug/sqrt(Hz) (400 ug/sqrt(Hz) one-sided): (0.283 / 0.2236)^2 = 1.60 s, and
        // (0.283 / 0.2)^2 = 2.00 s for a verification.
        let report = |capture_limit_s| Noise::Report { white_noise_g: [200e-6, 283e-6, 250e-6], capture_limit_s };
        let goal = rule(report(None)).goal();
        assert_eq!((goal.min_samples, goal.max_samples), (160, 160));
        let verification = rule(report(None)).verification_goal();
        assert_eq!((verification.min_samples, verification.max_samples), (200, 200));
        let goal = rule(report(Some(1.2))).goal();
        assert_eq!((goal.min_samples, goal.max_samples), (120, 120), "capped where longer stops helping");
    }

    #[test]
    fn a_noise_report_capture_limit_is_held_within_the_shortest_and_longest_capture() {
        // A tight target asks for (0.283 mg / 0.01 mg)^2 = 801 s: a 40 s report limit still stops at
        // the 8 s longest capture (800 samples at 100 Hz), and a 0.2 s limit at the 0.5 s shortest.
        let report = |capture_limit_s| Noise::Report { white_noise_g: [200e-6, 283e-6, 250e-6], capture_limit_s };
        let tight = |noise| StopRule { target_mg: 0.01, noise, rate_hz: 100 };
        let goal = tight(report(Some(40.0))).goal();
        assert_eq!((goal.min_samples, goal.max_samples), (800, 800), "a long limit is capped at 8 s");
        let goal = tight(report(Some(0.2))).goal();
        assert_eq!((goal.min_samples, goal.max_samples), (50, 50), "a limit under 0.5 s gives 0.5 s");
    }

    #[test]
    fn a_noise_report_is_read_from_noise_json_or_refused_by_name() {
        let path = Path::new("noise.json");
        let axis = |n: f64| format!("{{\"white_noise_density\": {n}}}");
        let json = format!(
            "{{\"accel_x\": {}, \"accel_y\": {}, \"accel_z\": {}, \"calibration\": {{\"capture_limit_s\": 40.0}}}}",
            axis(280.0),
            axis(290.0),
            axis(300.0)
        );
        let Noise::Report { white_noise_g, capture_limit_s } = noise_from_report(path, &json).unwrap() else {
            panic!()
        };
        let two_sided = [280e-6, 290e-6, 300e-6].map(|d: f64| d / std::f64::consts::SQRT_2);
        assert!(white_noise_g.iter().zip(two_sided).all(|(n, e)| (n - e).abs() < 1e-12), "{white_noise_g:?}");
        assert_eq!(capture_limit_s, Some(40.0));
        let bound = json.replace("40.0}", "40.0, \"capture_limit_is_lower_bound\": true}");
        let Noise::Report { capture_limit_s, .. } = noise_from_report(path, &bound).unwrap() else { panic!() };
        assert_eq!(capture_limit_s, None, "a lower bound caps nothing");
        let error = noise_from_report(path, "{\"accel_x\": {}}").unwrap_err().to_string();
        assert!(error.contains("noise.json cannot be used (it has no accel_x.white_noise_density)"), "{error}");
    }
}
