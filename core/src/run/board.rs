//! One board's calibration run, from its session begun to its verified result: the captures it
//! lacks (in arrival order with fixed-length captures, or adaptive), the fit and the gyro's G, the
//! person's answer to the upload, the session kept with what the board holds, the verification at
//! fresh orientations and the gyro's turn. The host begins the session (its file, its lock) and
//! afterwards certifies and reports it; every step between is here.

use std::time::Duration;

use shared::protocol::DeviceInfo;
use shared::Calibration;

use super::choice::{fit_with_gyro, show_choice, Fitted};
use super::stop_rule::{CaptureLength, StopRule};
use super::{
    capture_seconds, targets, verify_with, AdaptiveOptions, BoardClock, CollectOptions, Feedback, Hand, Moves,
    ProcedureError, TargetVerdict, TurnCheck, Turning, Verification, VERIFY_SECONDS,
};
use crate::link::{Link, LinkError, Transport};
use crate::run::resume;
use crate::session::{Session, SessionError, SessionKind};

/// Verification positions of an adaptive session: enough for an RMS, each as long as the target needs.
pub const ADAPTIVE_VERIFY_POSITIONS: u8 = 3;
/// Verification positions with fixed capture lengths (the guided procedure's classic count).
pub const FIXED_VERIFY_POSITIONS: u8 = 6;

/// How a board's run goes, as the host decided it from its arguments and the board.
#[derive(Clone)]
pub struct BoardPlan {
    /// The length of each capture when fixed (`--seconds`); a quick session's shortest by default.
    pub seconds: Option<u8>,
    /// An adaptive session's stop rule (its target and where its noise comes from).
    pub rule: Option<StopRule>,
    /// Fresh orientations to verify at (`--verify`), else the session kind's default.
    pub verify_positions: Option<u8>,
    /// How long to wait for a position (`None`: as long as the person takes).
    pub wait_limit: Option<Duration>,
    /// The board's clock.
    pub clock: BoardClock,
    /// Whether the session continues one begun in an earlier run.
    pub resumed: bool,
}

/// What the run needs of the people around it: what to tell and ask, who turns the board (a new
/// hand for the captures and one for the verification), and where the session is kept.
pub struct Around<'a> {
    pub feedback: &'a mut dyn Feedback,
    pub hands: &'a mut dyn FnMut() -> Box<dyn Hand>,
    pub keep: &'a mut dyn FnMut(&Session) -> Result<(), SessionError>,
}

/// A verified run: the calibrations chosen between, the verification, the gyro's turn, how long
/// the board was kept, the verdict against the target and the session as verified.
pub struct Calibrated {
    pub fitted: Fitted,
    pub verification: Verification,
    pub check: Option<TurnCheck>,
    pub board_seconds: Option<f64>,
    pub target: TargetVerdict,
    pub verified: Session,
}

/// Why a board's run stopped, by what the board holds then.
#[derive(Debug)]
pub enum RunError {
    /// Before anything was uploaded (the captures so far are kept).
    Stopped(ProcedureError),
    /// The session could not be kept with the calibration uploaded, before the verification.
    NotKept(SessionError),
    /// After the calibration was uploaded and saved on the board.
    AfterUpload(ProcedureError),
}

/// Runs `session` on the board behind `link` to its verified result; `None` when the person declined
/// the upload (the board keeps what it had).
pub async fn calibrate<T: Transport>(
    link: &mut Link<T>,
    info: &DeviceInfo,
    plan: &BoardPlan,
    around: Around<'_>,
    mut session: Session,
) -> Result<Option<Calibrated>, RunError> {
    let Around { feedback, hands, keep } = around;
    let stopped = RunError::Stopped;
    let (moves, first_capture_s) =
        collect(link, info, plan, hands(), feedback, &mut session, keep).await.map_err(stopped)?;
    let config = info.config;
    let fitted = fit_with_gyro(link, &session, plan.resumed, config, &moves, feedback).await.map_err(stopped)?;
    show_choice(feedback, &fitted);
    // NOTE: the captures are all kept by now: a Ctrl-C or a lost board here is resumed from them.
    if link.interrupted() {
        return Err(stopped(LinkError::Interrupted.into()));
    }
    if !upload_if_confirmed(link, &fitted.chosen, feedback).await.map_err(|e| stopped(e.into()))? {
        return Ok(None);
    }
    // NOTE: kept before the verification, so that a Ctrl-C or a pulled cable during it still leaves
    // the session saying what the board holds.
    keep(&resume::kept_before_verifying(&fitted.session, fitted.chosen)).map_err(RunError::NotKept)?;
    let first_capture_s = resume::board_time_start(first_capture_s, plan.resumed);
    verify(link, info, plan, hands(), feedback, fitted, first_capture_s).await.map(Some)
}

/// The captures the session lacks, kept after each one, and the moves between them; also the
/// board's clock when the first capture started (when the collection started, with fixed lengths).
async fn collect<T: Transport>(
    link: &mut Link<T>,
    info: &DeviceInfo,
    plan: &BoardPlan,
    mut hand: Box<dyn Hand>,
    feedback: &mut dyn Feedback,
    session: &mut Session,
    keep: &mut dyn FnMut(&Session) -> Result<(), SessionError>,
) -> Result<(Moves, Option<f64>), ProcedureError> {
    let mut moves = Moves::at(info.config.sample_rate_hz);
    let turning = Turning { hand: hand.as_mut(), moves: &mut moves };
    let first = match (session.kind, &plan.rule) {
        (SessionKind::Adaptive, Some(rule)) => {
            let options =
                AdaptiveOptions { rule: rule.clone(), wait_limit: plan.wait_limit, clock: Some(plan.clock.clone()) };
            let collected =
                super::collect_adaptive(link, turning, &targets(false), &options, feedback, session, keep).await?;
            collected.first_capture_s
        }
        _ => {
            let quick = session.kind == SessionKind::Quick;
            let options = CollectOptions {
                seconds: plan.seconds.unwrap_or_else(|| capture_seconds(quick)),
                wait_limit: plan.wait_limit,
            };
            let started = (plan.clock)();
            super::collect_into(link, turning, &targets(quick), &options, feedback, session, keep).await?;
            Some(started)
        }
    };
    Ok((moves, first))
}

/// Uploads and saves the calibration if the person agrees; whether it did. Ctrl-C at the question
/// ends the run at once (`Interrupted`).
async fn upload_if_confirmed<T: Transport>(
    link: &mut Link<T>,
    calibration: &Calibration,
    feedback: &mut dyn Feedback,
) -> Result<bool, LinkError> {
    if !feedback.confirm("Upload this calibration to the board and save it in flash?") {
        if link.interrupted() {
            return Err(LinkError::Interrupted);
        }
        feedback.say("not uploaded; the board keeps its previous calibration");
        return Ok(false);
    }
    link.set_calibration(*calibration).await?;
    link.save_calibration().await?;
    feedback.say("uploaded and saved; now checking it at fresh orientations");
    Ok(true)
}

/// The verification at fresh orientations and the gyro's turn on the uploaded calibration, and the
/// session as verified.
async fn verify<T: Transport>(
    link: &mut Link<T>,
    info: &DeviceInfo,
    plan: &BoardPlan,
    mut hand: Box<dyn Hand>,
    feedback: &mut dyn Feedback,
    fitted: Fitted,
    first_capture_s: Option<f64>,
) -> Result<Calibrated, RunError> {
    let kind = fitted.session.kind;
    let (positions, length) = verification(plan, kind);
    let calibrated: Vec<[f64; 3]> = fitted.session.captures.iter().map(|c| c.stats.mean_g.map(f64::from)).collect();
    let verification = verify_with(link, hand.as_mut(), positions, plan.wait_limit, feedback, &calibrated, length)
        .await
        .map_err(RunError::AfterUpload)?;
    let board_seconds = first_capture_s.map(|first| (plan.clock)() - first);
    let rate_hz = info.config.sample_rate_hz;
    let check = super::gyro::check(link, hand.as_mut(), rate_hz, &fitted.gyro, feedback)
        .await
        .map_err(RunError::AfterUpload)?;
    let target_mg = plan.rule.as_ref().filter(|_| kind == SessionKind::Adaptive).map(|rule| rule.target_mg);
    let target = verification.against(target_mg);
    let uploaded = Some(fitted.chosen);
    let verified = Session { verification: Some(verification.clone()), uploaded, ..fitted.session.clone() };
    Ok(Calibrated { fitted, verification, check, board_seconds, target, verified })
}

/// How many fresh orientations to verify at, and how long each capture runs.
fn verification(plan: &BoardPlan, kind: SessionKind) -> (usize, CaptureLength) {
    match (kind, &plan.rule) {
        (SessionKind::Adaptive, Some(rule)) => (
            usize::from(plan.verify_positions.unwrap_or(ADAPTIVE_VERIFY_POSITIONS)),
            CaptureLength::Goal(rule.verification_goal()),
        ),
        _ => (
            usize::from(plan.verify_positions.unwrap_or(FIXED_VERIFY_POSITIONS)),
            CaptureLength::Seconds(VERIFY_SECONDS),
        ),
    }
}

#[cfg(test)]
mod tests {
    //! The run's policies on a simulated board in this process: milliseconds, not a pty's minutes.

    use std::sync::atomic::{AtomicBool, Ordering};
    use std::sync::Arc;

    use embassy_futures::block_on;

    use super::*;
    use crate::limits::{DEFAULT_TARGET_MG, SIM_WAIT_LIMIT};
    use crate::run::stop_rule::Noise;
    use crate::session::BoardRecord;
    use crate::sim::{InProcess, SimulatedHand};

    /// A transport whose Ctrl-C flag the test sets.
    struct Interruptible {
        board: InProcess,
        interrupt: Arc<AtomicBool>,
    }

    impl Transport for Interruptible {
        async fn write(&mut self, bytes: &[u8]) -> Result<(), LinkError> {
            self.board.write(bytes).await
        }
        async fn read(&mut self, buffer: &mut [u8]) -> Result<usize, LinkError> {
            self.board.read(buffer).await
        }
        fn now(&self) -> Duration {
            self.board.now()
        }
        fn unix_time_s(&self) -> f64 {
            self.board.unix_time_s()
        }
        fn interrupted(&self) -> bool {
            self.interrupt.load(Ordering::SeqCst)
        }
    }

    /// The person: answers the upload question `yes` or not, presses Ctrl-C at it when asked to,
    /// and keeps what they were told.
    struct Person {
        yes: bool,
        ctrl_c_at_question: Option<Arc<AtomicBool>>,
        told: Vec<String>,
    }

    impl Feedback for Person {
        fn say(&mut self, line: &str) {
            self.told.push(line.to_owned());
        }
        fn live(&mut self, _: &str) {}
        fn progress(&mut self, _: u32, _: u32) {}
        fn progress_done(&mut self) {}
        fn confirm(&mut self, _: &str) -> bool {
            self.ctrl_c_at_question.iter().for_each(|flag| flag.store(true, Ordering::SeqCst));
            self.yes
        }
    }

    /// What a run left: its result, every session it kept (in order), what it said, and the board's
    /// active calibration afterwards.
    struct Ran {
        result: Result<Option<Calibrated>, RunError>,
        kept: Vec<Session>,
        person: Person,
        active: Option<Calibration>,
    }

    /// A default adaptive run of the simulated board of `seed`, with one verification position.
    fn run(seed: u64, yes: bool, ctrl_c_at_question: bool) -> Ran {
        run_session(seed, yes, ctrl_c_at_question, None)
    }

    /// As [`run`], going on with `resumed` when given (a session kept by an earlier run).
    fn run_session(seed: u64, yes: bool, ctrl_c_at_question: bool, resumed: Option<Session>) -> Ran {
        let board = InProcess::realistic(seed);
        let mut controls = vec![board.controls(), board.controls()];
        let clock = board.clock();
        let interrupt = Arc::new(AtomicBool::new(false));
        let mut link = Link::new(Interruptible { board, interrupt: interrupt.clone() });
        let pressed = ctrl_c_at_question.then(|| interrupt.clone());
        let mut person = Person { yes, ctrl_c_at_question: pressed, told: Vec::new() };
        let mut kept = Vec::new();
        let result = block_on(async {
            let info = link.hello().await.unwrap();
            let rule =
                StopRule { target_mg: DEFAULT_TARGET_MG, noise: Noise::Measured, rate_hz: info.config.sample_rate_hz };
            let plan = BoardPlan {
                seconds: None,
                rule: Some(rule),
                verify_positions: Some(1),
                wait_limit: Some(SIM_WAIT_LIMIT),
                clock,
                resumed: resumed.is_some(),
            };
            let begun =
                Session { board: Some(BoardRecord::of(&info)), kind: SessionKind::Adaptive, ..Session::default() };
            let session = resumed.unwrap_or(begun);
            let mut hands = || -> Box<dyn Hand> { Box::new(SimulatedHand::new(controls.remove(0), 3.0, seed)) };
            let mut keep = |session: &Session| {
                kept.push(session.clone());
                Ok(())
            };
            let around = Around { feedback: &mut person, hands: &mut hands, keep: &mut keep };
            calibrate(&mut link, &info, &plan, around, session).await
        });
        // NOTE: the flag is let go to ask the board what it holds after the run.
        interrupt.store(false, Ordering::SeqCst);
        let active = block_on(link.calibration(shared::protocol::CalibrationSlot::Active)).unwrap();
        Ran { result, kept, person, active }
    }

    #[test]
    fn the_session_is_kept_with_the_upload_before_the_verification_and_as_verified_after() {
        let ran = run(5, true, false);
        let calibrated = ran.result.unwrap().expect("uploaded");
        let last = ran.kept.last().expect("kept");
        assert_eq!(last.uploaded, Some(calibrated.fitted.chosen), "the last kept session says what the board holds");
        assert!(last.verification.is_none(), "kept before the verification, which it does not hold yet");
        assert_eq!(ran.active, Some(calibrated.fitted.chosen));
        assert_eq!(calibrated.verified.uploaded, Some(calibrated.fitted.chosen));
        assert_eq!(calibrated.verified.verification.as_ref().map(|v| v.positions), Some(1));
        let captures = calibrated.verified.captures.len();
        assert_eq!(ran.kept.len(), captures + 1, "one keep per capture, then the upload's");
        assert!(calibrated.board_seconds.is_some_and(|s| s > 0.0), "a run begun here claims its board time");
    }

    #[test]
    fn a_declined_upload_leaves_the_board_as_it_was_and_keeps_no_upload() {
        let ran = run(5, false, false);
        assert!(matches!(ran.result, Ok(None)));
        assert_eq!(ran.active, None, "the board held no calibration and holds none");
        assert!(ran.kept.iter().all(|s| s.uploaded.is_none()));
        assert!(ran.person.told.iter().any(|l| l == "not uploaded; the board keeps its previous calibration"));
    }

    #[test]
    fn ctrl_c_at_the_upload_question_stops_the_run_before_any_upload() {
        let ran = run(5, false, true);
        assert!(matches!(ran.result, Err(RunError::Stopped(ProcedureError::Link(LinkError::Interrupted)))));
        assert_eq!(ran.active, None);
        assert!(!ran.person.told.iter().any(|l| l.starts_with("not uploaded")), "{:?}", ran.person.told);
    }

    #[test]
    fn a_resumed_run_takes_no_kept_capture_again_claims_no_board_time_and_keeps_the_g_it_uploaded() {
        let first = run(6, true, false);
        let uploaded = first.result.unwrap().expect("uploaded").fitted.chosen;
        // Resumed partway: the captures kept stay as they were, the rest are taken, no board time is claimed.
        let partway = first.kept[4].clone();
        let calibrated = run_session(6, true, false, Some(partway.clone())).result.unwrap().expect("uploaded");
        assert_eq!(calibrated.verified.captures[..5], partway.captures[..], "the kept captures are not taken again");
        assert!(calibrated.verified.captures.len() > 5);
        assert_eq!(calibrated.board_seconds, None, "its first capture was taken in another run");
        // Resumed complete: nothing is turned, so the G uploaded before stays.
        let complete = first.kept.last().cloned().expect("kept");
        let calibrated = run_session(6, true, false, Some(complete.clone())).result.unwrap().expect("uploaded");
        assert_eq!(calibrated.verified.captures.len(), complete.captures.len(), "no capture taken again");
        assert_eq!(calibrated.fitted.chosen.gyro.matrix, uploaded.gyro.matrix, "nothing turned: the G uploaded stays");
    }
}
