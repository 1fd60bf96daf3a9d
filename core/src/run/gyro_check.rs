//! The gyro's verification: after the calibration is on the chip, one fresh quarter turn, streamed
//! corrected by the chip (w = G (w_raw - b(T))) and integrated on the host, set beside the angle the
//! calibrated accelerometer measured between the rests before and after it. As anyone using a gyro
//! does, what the rate reads at rest just before and after the turn is taken as zero: the bias
//! stored at calibration has drifted since by a few hundredths of a deg/s, which over a turn of
//! seconds would hide the scale error being checked.

use nalgebra::Matrix3;
use shared::orientation::angle_between_deg;
use shared::protocol::{Sample, StreamKind};

use super::moves::{Problem, Recording, Watch};
use super::{Feedback, Hand, ProcedureError};
use crate::fit::gyro::{rotate_up, GyroFit, Turn};
use crate::limits::MAX_CHECK_AXIS_ELEVATION_DEG;
use crate::limits::{MAX_MOVE_SECONDS, TURN_CHECK_ATTEMPTS, TURN_CHECK_REST_SECONDS};
use crate::link::{Link, StreamRequest, Transport};
use crate::session::TurnCheck;

/// Streams the board at rest, asks `hand` for a quarter turn, and streams until it rests again;
/// a turn that cannot be measured (about a tilted line, never at rest) is asked for again, said
/// why, up to [`TURN_CHECK_ATTEMPTS`] times. `Ok(Err(why))` when none could be measured.
pub async fn check_turn<T: Transport>(
    link: &mut Link<T>,
    hand: &mut dyn Hand,
    rate_hz: u16,
    fit: Option<&GyroFit>,
    feedback: &mut dyn Feedback,
) -> Result<Result<TurnCheck, String>, ProcedureError> {
    let mut why = String::new();
    for attempt in 1..=TURN_CHECK_ATTEMPTS {
        if attempt > 1 {
            feedback.say(&format!("{why}; once more ({attempt} of {TURN_CHECK_ATTEMPTS})"));
        }
        let (head, recorded) = stream_turn(link, hand, rate_hz, feedback).await?;
        match recorded.map_err(|problem| problem.to_string()).and_then(|r| measure(&head, &r.samples, rate_hz, fit)) {
            Ok(check) => return Ok(Ok(check)),
            Err(problem) => why = format!("gyro check: {problem}"),
        }
    }
    Ok(Err(format!("{why} (after {TURN_CHECK_ATTEMPTS} turns; the gyro was not checked)")))
}

/// The rest before the turn (its samples), and the turn with the rest after it, or why not.
async fn stream_turn<T: Transport>(
    link: &mut Link<T>,
    hand: &mut dyn Hand,
    rate_hz: u16,
    feedback: &mut dyn Feedback,
) -> Result<(Vec<Sample>, Result<Recording, Problem>), ProcedureError> {
    let rest = (TURN_CHECK_REST_SECONDS * f64::from(rate_hz)).ceil() as usize;
    let request = StreamRequest { kind: StreamKind::Calibrated, rate_hz, count: MAX_MOVE_SECONDS * u32::from(rate_hz) };
    // NOTE: the rest after the turn is taken from a still run a quarter longer than it, so that the
    // last instants of the turn (below the stillness threshold, not yet zero) stay out of it.
    let mut watch = Watch::new([0.0; 3], rest + rest / 4);
    let (mut head, mut asked) = (Vec::with_capacity(rest), None);
    let tally = link
        .stream_while(request, |sample| {
            if head.len() == rest {
                return watch.push(sample);
            }
            head.push(*sample);
            if head.len() == rest {
                asked = Some(hand.turn_quarter(feedback));
            }
            true
        })
        .await?;
    asked.transpose()?;
    Ok((head, watch.finish(tally.lost(), "the verification turn")))
}

/// The turn's tilt both ways, from the rest before (`head`), the move and the rest after: the angle
/// between the rests' up directions by the accelerometer, and by the gyro (the rest before's up
/// carried through the integrated turn); refused, with why, when the turn was not about a
/// horizontal line.
fn measure(head: &[Sample], moved: &[Sample], rate_hz: u16, fit: Option<&GyroFit>) -> Result<TurnCheck, String> {
    let tail = &moved[moved.len().saturating_sub(head.len())..];
    let (before, after) = (mean_accel(head), mean_accel(tail));
    let turn = Turn {
        rates_dps: moved.iter().map(|s| s.gyro_dps.map(f64::from)).collect(),
        interval_s: 1.0 / f64::from(rate_hz),
        bias_before_dps: mean_gyro(head),
        bias_after_dps: mean_gyro(tail),
        up_before: unit(before),
        up_after: unit(after),
    };
    let elevation_deg = shared::linalg::dot(turn_axis(&turn), turn.up_before).abs().min(1.0).asin().to_degrees();
    if elevation_deg > MAX_CHECK_AXIS_ELEVATION_DEG {
        return Err(format!(
            "gyro check: the turn was about a line {elevation_deg:.0} degrees from the horizontal, so the accelerometer \
             saw only part of it; turn the board over one of its edges (about a horizontal line) to check the gyro"
        ));
    }
    let tilt_deg = |g: &Matrix3<f64>| angle_between_deg(turn.up_before, rotate_up(&turn, g).into());
    let gyro_deg = tilt_deg(&Matrix3::identity());
    let undo = fit.and_then(|f| Matrix3::from(f.matrix).transpose().try_inverse());
    Ok(TurnCheck {
        accel_deg: angle_between_deg(before, after),
        accel_uncertainty_deg: accel_uncertainty_deg(head, tail),
        gyro_deg,
        gyro_uncertainty_deg: gyro_uncertainty_deg(head, &turn, gyro_deg, fit),
        raw_deg: undo.map(|g| tilt_deg(&g)),
    })
}

fn unit(v: [f64; 3]) -> [f64; 3] {
    let n = shared::linalg::norm(v).max(1e-12);
    v.map(|x| x / n)
}

fn mean_accel(samples: &[Sample]) -> [f64; 3] {
    mean_of(samples, |s| s.accel_g)
}

fn mean_gyro(samples: &[Sample]) -> [f64; 3] {
    mean_of(samples, |s| s.gyro_dps)
}

fn mean_of(samples: &[Sample], pick: impl Fn(&Sample) -> [f32; 3]) -> [f64; 3] {
    let n = samples.len().max(1) as f64;
    [0, 1, 2].map(|k| samples.iter().map(|s| f64::from(pick(s)[k])).sum::<f64>() / n)
}

/// Standard deviation of one axis over `samples`, from `pick`.
fn scatter(samples: &[Sample], pick: impl Fn(&Sample) -> f64) -> f64 {
    let n = samples.len().max(2) as f64;
    let mean = samples.iter().map(&pick).sum::<f64>() / n;
    (samples.iter().map(|s| (pick(s) - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt()
}

/// The angle between two mean directions of 1 g, each over n samples of scatter s per axis:
/// each mean is off by s / sqrt(n) across it, so the angle by sqrt(2) s / sqrt(n) radians.
fn accel_uncertainty_deg(head: &[Sample], tail: &[Sample]) -> f64 {
    let per_end = |samples: &[Sample]| {
        let s = (0..3).map(|k| scatter(samples, |x| f64::from(x.accel_g[k]))).fold(0.0, f64::max);
        s * s / samples.len().max(1) as f64
    };
    (per_end(head) + per_end(tail)).sqrt().to_degrees()
}

/// The integrated rate noise (per-sample scatter at rest times dt times sqrt(samples)), the error
/// of the bias taken at rest (scatter / sqrt(rest samples), over the turn's duration), and G's
/// standard errors projected on the turn's axis, added in quadrature.
fn gyro_uncertainty_deg(head: &[Sample], turn: &Turn, turned: f64, fit: Option<&GyroFit>) -> f64 {
    let rate_noise = (0..3).map(|k| scatter(head, |x| f64::from(x.gyro_dps[k]))).fold(0.0, f64::max);
    let samples = turn.rates_dps.len() as f64;
    let white_deg = rate_noise * turn.interval_s * samples.sqrt();
    let bias_deg = rate_noise / (head.len().max(1) as f64).sqrt() * turn.interval_s * samples;
    let noise_deg = white_deg.hypot(bias_deg);
    let axis = turn_axis(turn);
    let scale_var = fit.map_or(0.0, |f| {
        (0..3)
            .flat_map(|i| (0..3).map(move |j| (i, j)))
            .map(|(i, j)| (axis[i] * axis[j] * f.std_errors[i][j]).powi(2))
            .sum()
    });
    (noise_deg * noise_deg + turned * turned * scale_var).sqrt()
}

/// The unit direction of the summed rate: the axis of a turn about one line.
fn turn_axis(turn: &Turn) -> [f64; 3] {
    let sum = turn.rates_dps.iter().fold([0.0; 3], |a, r| shared::linalg::add(a, *r));
    let n = shared::linalg::norm(sum).max(1e-12);
    sum.map(|v| v / n)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 1 s at rest with `up` up, at 100 Hz.
    fn rest(up: [f32; 3]) -> Vec<Sample> {
        (0..100).map(|i| Sample { index: i, time_us: 0, accel_g: up, gyro_dps: [0.0; 3], temp_c: 25.0 }).collect()
    }

    /// A quarter turn at 90 deg/s about `axis` from +Z up, then 1 s at rest with `up_after` up.
    fn quarter_turn(axis: [f32; 3], up_after: [f32; 3]) -> Vec<Sample> {
        let rate = axis.map(|v| v * 90.0);
        let turning =
            (0..100).map(|i| Sample { index: i, time_us: 0, accel_g: up_after, gyro_dps: rate, temp_c: 25.0 });
        turning.chain(rest(up_after)).collect()
    }

    #[test]
    fn a_turn_over_an_edge_is_checked_and_one_about_the_vertical_is_refused() {
        let head = rest([0.0, 0.0, 1.0]);
        let check = measure(&head, &quarter_turn([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]), 100, None).unwrap();
        assert!((check.accel_deg - 90.0).abs() < 1e-4 && (check.gyro_deg - 90.0).abs() < 1e-3, "{check:?}");
        // About the vertical: the accelerometer sees no tilt at all, so nothing to compare.
        let why = measure(&head, &quarter_turn([0.0, 0.0, 1.0], [0.0, 0.0, 1.0]), 100, None).unwrap_err();
        assert!(why.contains("90 degrees from the horizontal"), "{why}");
    }

    #[test]
    fn a_turn_about_a_tilted_line_compares_the_tilt_the_gyro_predicts_with_the_accelerometers() {
        // 90 degrees about a line 15 degrees above the horizontal: the up direction turns by 86.6.
        let (s, c) = 15f32.to_radians().sin_cos();
        let axis = [c, 0.0, s];
        // NOTE: Rodrigues for a quarter turn: z -> (a x z) + a (a . z), the sign of y by the turn's sense.
        let up_after = [c * s, c, s * s];
        let turned = quarter_turn(axis, up_after);
        let check = measure(&rest([0.0, 0.0, 1.0]), &turned, 100, None).unwrap();
        let expected = (f64::from(s * s)).acos().to_degrees();
        assert!((check.gyro_deg - expected).abs() < 1e-2, "gyro {} vs {expected}", check.gyro_deg);
        assert!((check.accel_deg - expected).abs() < 1e-3, "accelerometer {} vs {expected}", check.accel_deg);
    }

    /// A hand whose first quarter turn goes about the vertical (nothing for the accelerometer to
    /// see), and whose later ones go over an edge as asked.
    struct SlipsOnce {
        hand: crate::sim::SimulatedHand,
        controls: crate::sim::BoardControls,
        slipped: bool,
    }

    impl Hand for SlipsOnce {
        fn present(
            &mut self,
            target: &crate::orientation::Orientation,
            f: &mut dyn Feedback,
        ) -> Result<(), ProcedureError> {
            self.hand.present(target, f)
        }
        fn fresh(&mut self, index: usize, f: &mut dyn Feedback) -> Result<(), ProcedureError> {
            self.hand.fresh(index, f)
        }
        fn turn_quarter(&mut self, f: &mut dyn Feedback) -> Result<(), ProcedureError> {
            if std::mem::replace(&mut self.slipped, true) {
                return self.hand.turn_quarter(f);
            }
            let about_the_vertical = crate::sim::turn::turning([0.0, 0.0, 1.0], 90.0);
            use crate::sim::Controls;
            self.controls.send(about_the_vertical).map_err(|_| ProcedureError::SimulatedBoardStopped)
        }
    }

    #[test]
    fn a_turn_that_cannot_be_measured_is_asked_for_again_and_the_next_one_is_checked() {
        let board = crate::sim::InProcess::realistic(3);
        let hand = crate::sim::SimulatedHand::new(board.controls(), 0.0, 3);
        let mut hand = SlipsOnce { hand, controls: board.controls(), slipped: false };
        let mut link = crate::link::Link::new(board);
        let mut told = crate::run::Told(Vec::new());
        let check = embassy_futures::block_on(async {
            let rate_hz = link.hello().await.unwrap().config.sample_rate_hz;
            check_turn(&mut link, &mut hand, rate_hz, None, &mut told).await.unwrap()
        });
        let check = check.unwrap_or_else(|why| panic!("{why}; told {:?}", told.0));
        // NOTE: the board holds no calibration: its raw accelerometer reads the quarter turn a few degrees off.
        assert!((check.accel_deg - 90.0).abs() < 5.0 && (check.gyro_deg - 90.0).abs() < 5.0, "{check:?}");
        let again = told.0.iter().find(|line| line.contains("once more (2 of 3)"));
        assert!(again.is_some_and(|l| l.contains("horizontal")), "{:?}", told.0);
    }
}
