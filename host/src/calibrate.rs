//! The guided calibration: ask for each position, see when the board is there and still, capture,
//! fit, upload, save, and verify at fresh orientations.

use std::time::{Duration, Instant};

use serde::Serialize;
use shared::calibration::GyroCalibration;
use shared::linalg;
use shared::orientation::angle_between_deg;
use shared::protocol::{CalibrationSlot, CaptureStats, DeviceError, Request, Response, StreamKind};
use shared::{AccelRange, Calibration};

use crate::client::Client;
use crate::error::{calibration_reason, Error};
use crate::fit::{self, Fit, FitOptions, ModelChoice};
use crate::port::Port;
use crate::session::{CaptureRecord, Session};

/// Largest accelerometer scatter, in g, of a board that counts as still for the live check.
const STILL_STD_G: f64 = 0.010;
/// Live-check window: samples at the stream rate.
const LIVE_RATE_HZ: u16 = 20;
const LIVE_SAMPLES: u32 = 10;
/// Captures of a position tried before giving up on a board that keeps moving.
const CAPTURE_ATTEMPTS: usize = 5;
/// Smallest angle, in degrees, between two verification orientations.
pub const FRESH_DEG: f64 = 20.0;
/// Length of each verification capture, in seconds.
pub const VERIFY_SECONDS: u8 = 5;

/// A position to capture: a name for the user and the direction that should point up.
#[derive(Debug, Clone, PartialEq)]
pub struct Target {
    /// "+X" ... "-Z" for the faces, "+X+Y+Z" ... for the corners.
    pub name: String,
    /// Unit vector of the body frame that should point up.
    pub up: [f64; 3],
    /// Largest tilt from `up`, in degrees, still accepted as this target.
    pub tolerance_deg: f64,
}

/// The six faces.
pub fn faces() -> Vec<Target> {
    shared::Position::ALL
        .iter()
        .map(|p| Target { name: p.name().to_owned(), up: p.specific_force_g(), tolerance_deg: 15.0 })
        .collect()
}

/// The eight corners of the cube (each 54.7 degrees from three faces): together with the faces they
/// spread 14 positions over the sphere, which the orientation-free fit needs.
pub fn corners() -> Vec<Target> {
    let mut corners = Vec::with_capacity(8);
    for sx in [1.0, -1.0] {
        for sy in [1.0, -1.0] {
            for sz in [1.0, -1.0] {
                let sign = |s: f64| if s > 0.0 { '+' } else { '-' };
                let name = format!("{}X{}Y{}Z", sign(sx), sign(sy), sign(sz));
                let up = linalg::scale([sx, sy, sz], 1.0 / 3f64.sqrt());
                corners.push(Target { name, up, tolerance_deg: 20.0 });
            }
        }
    }
    corners
}

/// What the user sees and answers.
pub trait Feedback {
    /// A line of instruction or result.
    fn say(&mut self, line: &str);
    /// The live state of the board (replaced by the next one).
    fn live(&mut self, line: &str);
    /// A capture's progress.
    fn progress(&mut self, samples: u32, total: u32);
    /// The capture ended.
    fn progress_done(&mut self);
    /// A yes/no question; `true` for yes.
    fn confirm(&mut self, question: &str) -> bool;
}

/// Who turns the board: a person, or the tool itself on the simulated board.
pub trait Hand {
    /// Turns (or asks to turn) the board to a target.
    fn present(&mut self, target: &Target, feedback: &mut dyn Feedback) -> Result<(), Error>;
    /// Turns (or asks to turn) the board to a fresh orientation for verification.
    fn fresh(&mut self, index: usize, feedback: &mut dyn Feedback) -> Result<(), Error>;
}

/// A person holding the board: instructions only.
pub struct PersonHand;

impl Hand for PersonHand {
    fn present(&mut self, target: &Target, feedback: &mut dyn Feedback) -> Result<(), Error> {
        feedback.say(&format!(
            "Rest the board with {} pointing up ({}), and hold it still.",
            target.name,
            describe(target)
        ));
        Ok(())
    }

    fn fresh(&mut self, index: usize, feedback: &mut dyn Feedback) -> Result<(), Error> {
        feedback.say(&format!(
            "Verification {}: rest the board in a new orientation, unlike the calibration positions, and hold it still.",
            index + 1
        ));
        Ok(())
    }
}

fn describe(target: &Target) -> String {
    if target.name.len() == 2 {
        format!("the {} axis printed on the board toward the sky", target.name)
    } else {
        "a corner up: tilt the board so that those three axes point equally upward".to_owned()
    }
}

/// How a calibration runs.
#[derive(Debug, Clone)]
pub struct CalibrateOptions {
    /// Only the six faces, fitted on the chip.
    pub quick: bool,
    /// Capture length, in seconds.
    pub seconds: u8,
    /// Fresh orientations to verify at.
    pub verify_positions: usize,
    /// Give up waiting for a position after this long (`None`: wait for the person).
    pub wait_limit: Option<Duration>,
}

/// The errors at the verification orientations, in mg.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Verification {
    /// Orientations checked.
    pub positions: usize,
    /// RMS of | |m| - 1 g | with the raw readings.
    pub before_rms_mg: f64,
    /// RMS of | |a| - 1 g | with the calibration.
    pub after_rms_mg: f64,
    /// Largest | |a| - 1 g | with the calibration.
    pub after_max_mg: f64,
    /// Largest difference between the chip's own corrected samples and the calibration applied to
    /// the raw capture, in mg: proof the chip applies what was verified (noise of 20 samples).
    pub on_chip_difference_mg: f64,
}

/// Captures every target, in whatever order the board arrives at them.
pub fn collect<P: Port>(
    client: &mut Client<P>,
    hand: &mut dyn Hand,
    targets: &[Target],
    options: &CalibrateOptions,
    feedback: &mut dyn Feedback,
) -> Result<Session, Error> {
    client.call(Request::ClearPositions)?;
    let mut remaining: Vec<Target> = targets.to_vec();
    let mut done: Vec<Target> = Vec::new();
    let mut session = Session::default();
    while !remaining.is_empty() {
        hand.present(&remaining[0], feedback)?;
        let (index, _) = wait_for_target(client, &remaining, &done, options.wait_limit, feedback)?;
        let target = remaining.remove(index);
        feedback.say(&format!("{} found; averaging for {} s", target.name, options.seconds));
        let (stats, position) = capture(client, options.seconds, feedback)?;
        session.captures.push(CaptureRecord {
            target: target.name.clone(),
            position: position.map(|p| p.name().to_owned()),
            unix_time_s: crate::session::unix_time_s(),
            stats,
        });
        done.push(target);
        feedback.say(&format!("captured {} of {}", done.len(), targets.len()));
    }
    Ok(session)
}

/// Waits until the board rests within tolerance of one of the remaining targets; says how far it
/// is and refuses a position already captured.
fn wait_for_target<P: Port>(
    client: &mut Client<P>,
    remaining: &[Target],
    done: &[Target],
    limit: Option<Duration>,
    feedback: &mut dyn Feedback,
) -> Result<(usize, [f64; 3]), Error> {
    if remaining.is_empty() {
        return Err(Error::Refused("no position left to capture".into()));
    }
    let gave_up = || {
        let wanted: Vec<&str> = remaining.iter().map(|t| t.name.as_str()).collect();
        format!("the board never came to rest at any of {}; place it and run the command again", wanted.join(", "))
    };
    wait_for_rest(client, limit, feedback, gave_up, |mean, still| {
        let tilt = |t: &Target| angle_between_deg(mean, t.up);
        let Some((index, nearest)) = remaining.iter().enumerate().min_by(|a, b| tilt(a.1).total_cmp(&tilt(b.1))) else {
            return ("no position left to capture".into(), None);
        };
        if let Some(repeat) = done.iter().find(|t| tilt(t) < t.tolerance_deg.min(tilt(nearest))) {
            return (format!("{} is already captured: turn the board to {}", repeat.name, nearest.name), None);
        }
        let motion = if still { "still" } else { "moving" };
        let line = format!("{:.1} degrees from {} ({motion})", tilt(nearest), nearest.name);
        (line, (still && tilt(nearest) <= nearest.tolerance_deg).then_some((index, mean)))
    })
}

/// Streams live windows, showing what `judge` says of each, until two windows in a row are accepted
/// (`judge` returns a value only for a window that is still and where it should be); gives up after
/// `limit` with the line `gave_up` makes.
fn wait_for_rest<P: Port, R>(
    client: &mut Client<P>,
    limit: Option<Duration>,
    feedback: &mut dyn Feedback,
    gave_up: impl Fn() -> String,
    mut judge: impl FnMut([f64; 3], bool) -> (String, Option<R>),
) -> Result<R, Error> {
    let started = Instant::now();
    let mut accepted_in_a_row = 0;
    loop {
        if limit.is_some_and(|l| started.elapsed() > l) {
            return Err(Error::Refused(gave_up()));
        }
        let (mean, still) = live_window(client)?;
        let (line, verdict) = judge(mean, still);
        feedback.live(&line);
        match verdict {
            Some(value) if accepted_in_a_row >= 1 => return Ok(value),
            Some(_) => accepted_in_a_row += 1,
            None => accepted_in_a_row = 0,
        }
    }
}

/// Half a second of raw samples: their mean direction and whether the board was still.
fn live_window<P: Port>(client: &mut Client<P>) -> Result<([f64; 3], bool), Error> {
    let mut samples = Vec::with_capacity(LIVE_SAMPLES as usize);
    let request = Request::Stream { kind: StreamKind::Raw, rate_hz: LIVE_RATE_HZ, count: LIVE_SAMPLES };
    client.run(request, |update| {
        if let Response::Sample(sample) = update {
            samples.push(sample.accel_g.map(f64::from));
        }
    })?;
    let n = samples.len().max(1) as f64;
    let mean = [0, 1, 2].map(|k| samples.iter().map(|s| s[k]).sum::<f64>() / n);
    let spread = [0, 1, 2]
        .map(|k| (samples.iter().map(|s| (s[k] - mean[k]).powi(2)).sum::<f64>() / n).sqrt())
        .into_iter()
        .fold(0.0, f64::max);
    Ok((mean, spread < STILL_STD_G && !samples.is_empty()))
}

/// One capture, retried while the board moves.
fn capture<P: Port>(
    client: &mut Client<P>,
    seconds: u8,
    feedback: &mut dyn Feedback,
) -> Result<(CaptureStats, Option<shared::Position>), Error> {
    for attempt in 1..=CAPTURE_ATTEMPTS {
        let result = client.run(Request::Capture { seconds }, |update| {
            if let Response::Progress(p) = update {
                feedback.progress(p.samples, p.total_samples);
            }
        });
        feedback.progress_done();
        match result {
            Ok(Response::Captured { stats, position }) => return Ok((stats, position)),
            Ok(other) => return Err(Error::Protocol(format!("{other:?}"))),
            Err(Error::Device(error @ DeviceError::Moved { .. })) if attempt < CAPTURE_ATTEMPTS => {
                feedback.say(&format!("{}; trying again", crate::error::explain(&error)));
            }
            Err(error) => return Err(error),
        }
    }
    Err(Error::Refused("the board kept moving".into()))
}

/// The calibration for the device from a host fit over a session's captures (in g).
pub fn calibration_from_fit(fit: &Fit, session: &Session, range: AccelRange) -> Result<Calibration, Error> {
    let n = session.captures.len().max(1) as f32;
    let gyro_bias = session
        .captures
        .iter()
        .fold([0.0f32; 3], |sum, c| linalg::add(sum, linalg::scale(c.stats.gyro_mean_dps, 1.0 / n)));
    let temp_c = session.captures.iter().map(|c| c.stats.temp_c).sum::<f32>() / n;
    let evaluation = fit::evaluate(&session.dataset(), &fit.matrix, &fit.offset, 1.0, &fit.lines_used);
    let residual_mg = evaluation.rms_norm_error(true).unwrap_or(0.0) * 1000.0;
    let calibration = Calibration {
        matrix: fit.matrix.map(|row| row.map(|v| v as f32)),
        offset_g: fit.offset.map(|v| v as f32),
        gyro: GyroCalibration { bias_dps: gyro_bias, ..GyroCalibration::default() },
        origin: fit.model.origin(),
        range,
        mean_temp_c: temp_c,
        temperature: None,
        residual_mg: residual_mg as f32,
    };
    calibration.validate().map_err(|reason| {
        Error::Refused(format!("the {} fit is implausible: {}", fit.model.name(), calibration_reason(&reason)))
    })?;
    Ok(calibration)
}

/// The host's orientation-free fit of a session (the model `auto` picks for captures without known
/// orientations), or an error naming what the captures lack.
pub fn host_fit(session: &Session) -> Result<Fit, Error> {
    Ok(fit::fit(&session.dataset(), ModelChoice::Auto, &FitOptions::default())?)
}

/// The on-chip six-position fit from the captures the device kept.
pub fn chip_fit<P: Port>(client: &mut Client<P>) -> Result<Calibration, Error> {
    match client.call(Request::FitSixPosition)? {
        Response::Fitted(calibration) => Ok(calibration),
        other => Err(Error::Protocol(format!("{other:?}"))),
    }
}

/// Makes a calibration active on the device and stores it in flash.
pub fn upload_and_save<P: Port>(client: &mut Client<P>, calibration: &Calibration) -> Result<(), Error> {
    client.call(Request::SetCalibration(*calibration))?;
    client.call(Request::SaveCalibration)?;
    Ok(())
}

/// Checks the active calibration at fresh orientations: | |a| - 1 g | before and after, and that
/// the chip's own corrected samples agree with it.
pub fn verify<P: Port>(
    client: &mut Client<P>,
    hand: &mut dyn Hand,
    positions: usize,
    wait_limit: Option<Duration>,
    feedback: &mut dyn Feedback,
) -> Result<Verification, Error> {
    let calibration = match client.call(Request::GetCalibration(CalibrationSlot::Active))? {
        Response::Calibration(Some(calibration)) => calibration,
        Response::Calibration(None) => {
            return Err(Error::Refused(
                "the device has no active calibration to verify: calibrate or upload one first".into(),
            ))
        }
        other => return Err(Error::Protocol(format!("{other:?}"))),
    };
    let (mut before, mut after, mut on_chip) = (Vec::new(), Vec::new(), 0.0f64);
    let mut used = Vec::with_capacity(positions);
    for index in 0..positions {
        hand.fresh(index, feedback)?;
        used.push(wait_for_fresh(client, &used, wait_limit, feedback)?);
        let (stats, _) = capture(client, VERIFY_SECONDS, feedback)?;
        let raw = stats.mean_g;
        let corrected = calibration.apply(raw);
        before.push((f64::from(linalg::norm(raw)) - 1.0) * 1000.0);
        after.push((f64::from(linalg::norm(corrected)) - 1.0) * 1000.0);
        let chip_mean = chip_corrected_mean(client)?;
        on_chip = on_chip.max(f64::from(linalg::norm(linalg::sub(chip_mean, corrected))) * 1000.0);
        feedback.say(&format!(
            "verification {}: | |a| - 1 g | {:.2} mg raw, {:.3} mg calibrated",
            index + 1,
            before[index].abs(),
            after[index].abs()
        ));
    }
    let rms = |v: &[f64]| (v.iter().map(|e| e * e).sum::<f64>() / v.len().max(1) as f64).sqrt();
    Ok(Verification {
        positions,
        before_rms_mg: rms(&before),
        after_rms_mg: rms(&after),
        after_max_mg: after.iter().fold(0.0, |m, e| m.max(e.abs())),
        on_chip_difference_mg: on_chip,
    })
}

/// Waits until the board rests at an orientation at least [`FRESH_DEG`] from every one in `used`;
/// returns it.
fn wait_for_fresh<P: Port>(
    client: &mut Client<P>,
    used: &[[f64; 3]],
    limit: Option<Duration>,
    feedback: &mut dyn Feedback,
) -> Result<[f64; 3], Error> {
    let gave_up = || {
        "the board never came to rest at a new orientation; turn it and hold it still, then run the command again"
            .to_owned()
    };
    wait_for_rest(client, limit, feedback, gave_up, |mean, still| {
        let fresh = used.iter().all(|u| angle_between_deg(mean, *u) >= FRESH_DEG);
        let line = match (still, fresh) {
            (_, false) => "this orientation was already verified: turn the board to a new one",
            (false, true) => "moving: hold the board still",
            (true, true) => "still",
        };
        (line.to_owned(), (still && fresh).then_some(mean))
    })
}

/// Mean of 20 samples corrected by the chip itself.
fn chip_corrected_mean<P: Port>(client: &mut Client<P>) -> Result<[f32; 3], Error> {
    let mut sum = [0.0f32; 3];
    let mut count = 0u32;
    client.run(Request::Stream { kind: StreamKind::Calibrated, rate_hz: LIVE_RATE_HZ, count: 20 }, |update| {
        if let Response::Sample(sample) = update {
            sum = linalg::add(sum, sample.accel_g);
            count += 1;
        }
    })?;
    Ok(linalg::scale(sum, 1.0 / count.max(1) as f32))
}
