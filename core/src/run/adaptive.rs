//! A calibration that stops when it knows enough: positions in drift-cancelling order (A ... Z ... A),
//! each averaged until its mean is known well enough ([`StopRule`]), and no more positions once the
//! fit predicts the target accuracy at a fresh orientation. The collection loop is `collect`'s; this
//! is the order it asks in.

use std::sync::Arc;
use std::time::Duration;

use super::drift;
use super::stop_rule::StopRule;
use super::wanted::Wanted;
use super::{Feedback, Hand, Orientation};
use crate::limits::{MAX_CAPTURE_SECONDS, MIN_ADAPTIVE_POSITIONS};
use crate::session::Session;

/// A reader of the board's clock, in seconds (the simulated board's own time).
pub type BoardClock = Arc<dyn Fn() -> f64 + Send + Sync>;

/// How an adaptive calibration runs.
#[derive(Clone)]
pub struct AdaptiveOptions {
    /// When each capture stops.
    pub rule: StopRule,
    /// Give up waiting for a position after this long (`None`: wait for the person).
    pub wait_limit: Option<Duration>,
    /// The board's clock, when it has one the host can read (the simulated board).
    pub clock: Option<BoardClock>,
}

/// Where an adaptive collection is in its order: the positions, the rule, and whether it has
/// stopped asking for new ones (the fit predicts the target, or none is left).
pub(super) struct AdaptiveOrder {
    order: Vec<Orientation>,
    rule: StopRule,
    stopped: bool,
}

impl AdaptiveOrder {
    /// `targets` in drift-cancelling order under `rule`.
    pub(super) fn new(targets: &[Orientation], rule: StopRule) -> Self {
        AdaptiveOrder { order: drift::order(targets), rule, stopped: false }
    }

    /// The rule each capture stops by.
    pub(super) fn rule(&self) -> &StopRule {
        &self.rule
    }

    /// The next position not yet captured while the fit does not predict the target (the hand
    /// judges that for every board it turns), then the first position again; `None` once closed.
    pub(super) fn next(
        &mut self,
        session: &Session,
        hand: &mut dyn Hand,
        feedback: &mut dyn Feedback,
    ) -> Option<Wanted> {
        if !self.stopped {
            if let Some(target) = self.order.iter().find(|t| !session.has_capture(&t.name)) {
                if !hand.all_have_enough(enough(session, self.rule.target_mg, feedback)) {
                    return Some(Wanted { positions: vec![target.clone()], done: Vec::new(), closing: false });
                }
            } else {
                say_prediction(session, self.rule.target_mg, feedback);
            }
            self.stopped = true;
        }
        let closing = drift::closing(&self.order[0]);
        let closed = session.captures.iter().any(|c| c.closing);
        (!closed).then(|| Wanted { positions: vec![closing], done: Vec::new(), closing: true })
    }
}

/// Whether the session's fit already predicts the target at a fresh orientation (said when it does),
/// and, when the temperature moved, the closing capture will let the drift be fitted.
// NOTE: the prediction is that of the captures corrected for a fitted drift; stopped before the
// drift can be fitted, a warming board kept it in the calibration (--target-mg 0.5, seed 2: 1.04 mg
// at verification where 0.43 was predicted).
fn enough(session: &Session, target_mg: f64, feedback: &mut dyn Feedback) -> bool {
    if session.captures.len() < mutant!("adaptive-ends-from-nine", MIN_ADAPTIVE_POSITIONS, 9)
        || drift::unfitted_after(session, 1)
    {
        return false;
    }
    let Some(predicted_mg) = predicted_mg(session) else {
        return false;
    };
    let reached = predicted_mg <= target_mg;
    if reached {
        feedback.say(&prediction_line(session, predicted_mg, target_mg));
    }
    reached
}

/// The error the session's fit predicts at a fresh orientation, in mg (`None` without a fit).
fn predicted_mg(session: &Session) -> Option<f64> {
    session.fit().ok().and_then(|(f, _)| f.prediction).map(|p| p.norm_error_mg)
}

/// Says what the fit of every position taken predicts, once no position is left to ask for.
fn say_prediction(session: &Session, target_mg: f64, feedback: &mut dyn Feedback) {
    if let Some(predicted_mg) = predicted_mg(session) {
        feedback.say(&prediction_line(session, predicted_mg, target_mg));
    }
}

/// "N positions predict P mg ...", and why when P misses the target.
fn prediction_line(session: &Session, predicted_mg: f64, target_mg: f64) -> String {
    let n = session.positions();
    let head = format!("{n} positions predict {predicted_mg:.3} mg at a fresh orientation at their mean temperature");
    if predicted_mg <= target_mg {
        return format!("{head}, the {target_mg} mg wanted");
    }
    let longest = session.captures.iter().filter(|c| f64::from(c.stats.seconds) >= MAX_CAPTURE_SECONDS - 0.01).count();
    let why = match longest {
        0 => String::new(),
        k => format!(
            ", {k} of them averaged for the longest capture ({MAX_CAPTURE_SECONDS} s): this sensor's noise allows no better"
        ),
    };
    format!("{head}, not the {target_mg} mg wanted: every position is taken{why}; a larger --target-mg ends sooner")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::session::CaptureRecord;
    use crate::session::SessionKind;
    use shared::protocol::CaptureStats;
    use shared::AccelRange;

    fn captured(name: &str, seconds: f32) -> CaptureRecord {
        let stats = CaptureStats {
            samples: (seconds * 100.0) as u32,
            seconds,
            mean_g: [0.0, 0.0, 1.0],
            std_g: [2.8e-3; 3],
            gyro_mean_dps: [0.0; 3],
            gyro_std_dps: [0.05; 3],
            temp_c: 25.0,
            clipped: 0,
            range: AccelRange::G2,
        };
        crate::session::CaptureRecord::at(name, None, None, stats, 0.0)
    }

    #[test]
    fn the_prediction_counts_positions_not_the_closing_capture_and_says_why_it_misses() {
        let closing = CaptureRecord { closing: true, ..captured("+Z again", 8.0) };
        let captures = vec![captured("+Z", 8.0), captured("-Z", 8.0), captured("+X", 2.0), closing];
        let session = Session { captures, ..Session::default() };
        let reached = prediction_line(&session, 0.19, 0.2);
        assert!(
            reached.starts_with("3 positions predict 0.190 mg") && reached.ends_with("the 0.2 mg wanted"),
            "{reached}"
        );
        let missed = prediction_line(&session, 0.081, 0.05);
        assert!(missed.contains("not the 0.05 mg wanted: every position is taken, 3 of them averaged for the longest"));
        // Captures that stopped by their rule: no claim about the longest capture.
        let short = Session { captures: vec![captured("+Z", 2.0), captured("-Z", 2.0)], ..Session::default() };
        let missed = prediction_line(&short, 0.3, 0.2);
        assert!(missed.ends_with("not the 0.2 mg wanted: every position is taken; a larger --target-mg ends sooner"));
    }

    /// A session of `n` positions of a sensor read through a scale error and an offset, each mean
    /// off by a few hundredths of a mg as noise would leave it.
    fn positions_of_a_good_sensor(n: usize) -> Session {
        let directions: [[f32; 3]; 10] = [
            [0.0, 0.0, 1.0],
            [0.0, 0.0, -1.0],
            [1.0, 0.0, 0.0],
            [-1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, -1.0, 0.0],
            [0.577, 0.577, 0.577],
            [-0.577, 0.577, -0.577],
            [0.707, -0.707, 0.0],
            [0.0, -0.707, 0.707],
        ];
        let captures = directions[..n]
            .iter()
            .enumerate()
            .map(|(k, d)| {
                let wiggle = if k % 2 == 0 { 3e-5 } else { -3e-5 };
                let mut capture = captured(&format!("p{k}"), 8.0);
                capture.stats.mean_g = [1.01 * d[0] + 0.02 + wiggle, 0.99 * d[1] - 0.01, d[2] + 0.03 - wiggle];
                capture.stats.samples = 800;
                capture
            })
            .collect();
        Session { captures, kind: SessionKind::Adaptive, ..Session::default() }
    }

    #[test]
    fn a_prediction_ends_the_session_only_from_ten_positions_on() {
        let mut said = crate::run::Silent { yes: true };
        assert!(!enough(&positions_of_a_good_sensor(9), 1.0, &mut said), "nine positions are one too few");
        assert!(enough(&positions_of_a_good_sensor(10), 1.0, &mut said), "ten positions that predict the target");
    }
}
