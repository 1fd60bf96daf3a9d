//! The position wait of the guided calibration accepts a position only after two seconds of live
//! windows in a row (four of half a second) still and at the target, counted from the prompt: a board
//! already lying there is not captured at once, and a moving window starts the count again; the same
//! holds for the verification's wait for a fresh orientation. Driven by a scripted device that serves each live window from a script and logs every
//! request, so the test sees exactly when the capture was asked for.

use std::sync::{Arc, Mutex};
use std::time::Duration;

use accelcal::link::{pipe, Client, PipeEnd};
use accelcal::procedure::{self as calibrate, CollectOptions, Feedback, PersonHand};
use accelcal_tests::scripted::{self, frame};
use shared::protocol::{CaptureStats, DeviceError, Request, Response, Sample, StreamKind};
use shared::{AccelRange, Calibration, Position};

/// One live window as the script serves it.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Window {
    /// At +Z up, with a scatter of 1 mg (the still limit is 10 mg).
    Still,
    /// At +Z up, swinging by 50 mg.
    Moving,
}

/// Samples of a window: +Z up, alternating by the window's swing.
fn samples(id: u16, window: Window, count: u32) -> Vec<u8> {
    let swing = if window == Window::Still { 0.001 } else { 0.05 };
    let sample = |i: u32| {
        let sign = if i.is_multiple_of(2) { 1.0 } else { -1.0 };
        let accel_g = [sign * swing, -sign * swing, 1.0];
        frame(
            id,
            &Response::Sample(Sample {
                index: i,
                time_us: u64::from(i) * 10_000,
                accel_g,
                gyro_dps: [0.0; 3],
                temp_c: 25.0,
            }),
        )
    };
    let mut frames: Vec<Vec<u8>> = (0..count).map(sample).collect();
    frames.push(frame(id, &Response::StreamEnded { samples: count, dropped: 0 }));
    frames.concat()
}

fn captured(id: u16, mean_g: [f32; 3]) -> Vec<u8> {
    let stats = CaptureStats {
        samples: 500,
        seconds: 5.0,
        mean_g,
        std_g: [0.001; 3],
        gyro_mean_dps: [0.0; 3],
        gyro_std_dps: [0.01; 3],
        temp_c: 25.0,
        clipped: 0,
        range: AccelRange::G2,
    };
    frame(id, &Response::Captured { stats, position: Some(Position::PosZ) })
}

/// A client on a scripted device that serves the live windows of `script` (the last one repeats) and
/// logs each request by kind; every capture reads +Z.
fn scripted_client(script: &[Window]) -> (Client<PipeEnd>, Arc<Mutex<Vec<&'static str>>>) {
    scripted_client_capturing(script, &[[0.0, 0.0, 1.0]])
}

/// As [`scripted_client`], the captures reading the means of `captures` in turn (the last repeats).
fn scripted_client_capturing(
    script: &[Window],
    captures: &[[f32; 3]],
) -> (Client<PipeEnd>, Arc<Mutex<Vec<&'static str>>>) {
    let log = Arc::new(Mutex::new(Vec::new()));
    let (host, device) = pipe();
    let (device_log, mut windows, mut means) = (Arc::clone(&log), script.to_vec(), captures.to_vec());
    let _device = scripted::spawn(device, move |id, request| {
        let (kind, answer) = match request {
            Request::ClearPositions => ("clear", frame(id, &Response::Done)),
            Request::GetCalibration(_) => {
                ("get", frame(id, &Response::Calibration(Some(Calibration::identity(AccelRange::G2)))))
            }
            Request::Stream { kind: StreamKind::Calibrated, count, .. } => {
                ("calibrated", samples(id, Window::Still, count))
            }
            Request::Stream { count, .. } => {
                let window = if windows.len() > 1 { windows.remove(0) } else { windows[0] };
                ("window", samples(id, window, count))
            }
            Request::Capture { .. } => {
                let mean = if means.len() > 1 { means.remove(0) } else { means[0] };
                ("capture", captured(id, mean))
            }
            _ => ("other", frame(id, &Response::Error(DeviceError::Busy))),
        };
        device_log.lock().unwrap().push(kind);
        answer
    });
    let (client, _) = Client::connect(host).expect("the scripted device says hello");
    (client, log)
}

/// Runs the position wait for +Z against `script`; returns the requests the device saw, by kind,
/// and the live lines shown.
fn wait_for_z(script: &[Window]) -> (Vec<&'static str>, Vec<String>) {
    let (mut client, log) = scripted_client(script);
    let target = calibrate::faces().into_iter().find(|t| t.name == "+Z").expect("a +Z face");
    let options = CollectOptions { seconds: 5, wait_limit: Some(Duration::from_secs(20)) };
    let mut feedback = LiveLines::default();
    let session = calibrate::collect(&mut client, &mut PersonHand, &[target], &options, &mut feedback).unwrap();
    assert_eq!(session.captures.len(), 1);
    let requests = log.lock().unwrap().clone();
    (requests, feedback.0)
}

/// A feedback that keeps the live lines.
#[derive(Default)]
struct LiveLines(Vec<String>);

impl Feedback for LiveLines {
    fn say(&mut self, _: &str) {}
    fn live(&mut self, line: &str) {
        self.0.push(line.to_owned());
    }
    fn progress(&mut self, _: u32, _: u32) {}
    fn progress_done(&mut self) {}
    fn confirm(&mut self, _: &str) -> bool {
        true
    }
}

#[test]
fn a_board_already_at_the_target_is_captured_only_after_two_seconds_still_after_the_prompt() {
    let (requests, live) = wait_for_z(&[Window::Still]);
    assert_eq!(requests, ["clear", "window", "window", "window", "window", "capture"]);
    assert_eq!(live, ["0.0 degrees from +Z (still)"; 4]);
}

#[test]
fn fewer_still_windows_are_not_enough_and_a_moving_one_starts_the_count_again() {
    use Window::{Moving, Still};
    let (requests, live) = wait_for_z(&[Still, Moving, Still, Still, Still, Moving, Still]);
    // Still, moving (count back to zero), three still, moving, then still (repeating): accepted at
    // the 4th still window after the last moving one, the 10th window.
    let mut expected = vec!["clear"];
    expected.extend(["window"; 10]);
    expected.push("capture");
    assert_eq!(requests, expected);
    assert_eq!((live[1].as_str(), live[5].as_str()), ("0.0 degrees from +Z (moving)", "0.0 degrees from +Z (moving)"));
    assert_eq!(live.len(), 10, "{live:?}");
}

#[test]
fn the_verification_waits_for_two_seconds_of_still_windows_too() {
    use Window::{Moving, Still};
    let (mut client, log) = scripted_client(&[Still, Moving, Still, Still]);
    let mut feedback = LiveLines::default();
    let wait = Some(Duration::from_secs(20));
    let verification = calibrate::verify(&mut client, &mut PersonHand, 1, wait, &mut feedback).unwrap();
    assert_eq!(verification.positions, 1);
    let requests = log.lock().unwrap().clone();
    assert_eq!(requests, ["get", "window", "window", "window", "window", "window", "window", "capture", "calibrated"]);
    assert_eq!(feedback.0, ["still", "moving: hold the board still", "still", "still", "still", "still"]);
}

#[test]
fn the_verification_never_takes_an_orientation_the_calibration_was_captured_at() {
    // The board stays at +Z, where the calibration's last capture was taken.
    let (mut client, _) = scripted_client(&[Window::Still]);
    let mut feedback = LiveLines::default();
    let wait = Some(Duration::from_millis(500));
    let result = calibrate::verify_clear_of(&mut client, &mut PersonHand, 1, wait, &mut feedback, &[[0.0, 0.01, 0.98]]);
    // The stop carries what was verified before it (none here), around the cause.
    let Err(calibrate::ProcedureError::VerificationStopped { source, .. }) = &result else { panic!("{result:?}") };
    assert!(matches!(**source, calibrate::ProcedureError::NeverFresh), "{result:?}");
    assert!(!feedback.0.is_empty());
    assert!(feedback.0.iter().all(|line| line.starts_with("this orientation was used already")), "{:?}", feedback.0);
}

#[test]
fn a_capture_that_ends_at_another_orientation_is_not_kept_under_the_wanted_name() {
    // The person turned the board from +Z to +X during the first capture and held it there: the
    // capture reads +X. It must not be recorded as +Z; the wait starts again and the next capture,
    // at +Z, is the one kept.
    let (mut client, log) = scripted_client_capturing(&[Window::Still], &[[1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]);
    let target = calibrate::faces().into_iter().find(|t| t.name == "+Z").expect("a +Z face");
    let options = CollectOptions { seconds: 5, wait_limit: Some(Duration::from_secs(20)) };
    let mut feedback = LiveLines::default();
    let session = calibrate::collect(&mut client, &mut PersonHand, &[target], &options, &mut feedback).unwrap();
    assert_eq!(session.captures.len(), 1);
    assert_eq!(session.captures[0].stats.mean_g, [0.0, 0.0, 1.0], "the +X reading was kept as +Z");
    let captures = log.lock().unwrap().iter().filter(|kind| **kind == "capture").count();
    assert_eq!(captures, 2);
}
