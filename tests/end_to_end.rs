//! The whole calibration over a real pseudo-terminal with the real `serialport` crate, the board's
//! restart on the same flash, and every named failure as one line with its cause and remedy.

use std::sync::mpsc::Sender;
use std::time::Duration;

use accelcal::link::{open_serial, pipe, Client, LinkError, Port};
use accelcal::procedure::{self, CollectOptions, Feedback, Hand, Orientation, ProcedureError, Silent};
use accelcal::session::SessionFiles;
use accelcal::sim::SimulatedHand;
use accelcal::sim::{SimBoard, SimCommand};
use firmware::sim::physics::Motion;
use firmware::sim::SimFlash;
use serialport::TTYPort;
use shared::protocol::{ActiveCalibration, CalibrationSlot, DeviceError, Request, Response};
use shared::Position;

const PLACEMENT_DEG: f64 = 3.0;
const WAIT: Option<Duration> = Some(Duration::from_secs(30));

/// A simulated board serving a fresh pseudo-terminal; the slave end is kept open for its lifetime.
struct PtyBoard {
    board: SimBoard,
    path: String,
    _slave: TTYPort,
}

fn pty_board(flash: SimFlash, seed: u64) -> PtyBoard {
    let (master, slave) = TTYPort::pair().expect("a pseudo-terminal");
    let path = serialport::SerialPort::name(&slave).expect("a named pseudo-terminal");
    PtyBoard { board: SimBoard::spawn(master, flash, seed), path, _slave: slave }
}

fn connect_serial(path: &str) -> Client<Box<dyn Port>> {
    let port = open_serial(path, accelcal::link::port::DEFAULT_BAUD).expect("the pseudo-terminal opens");
    Client::connect(Box::new(port) as Box<dyn Port>).expect("the simulated board answers").0
}

fn options() -> CollectOptions {
    CollectOptions { seconds: 10, wait_limit: WAIT }
}

#[test]
fn default_calibration_over_a_pty_survives_a_restart_and_verifies_below_1_mg() {
    let pty = pty_board(SimFlash::new(), 11);
    let mut client = connect_serial(&pty.path);
    let mut hand = SimulatedHand::new(pty.board.controls(), PLACEMENT_DEG, 11);
    let mut feedback = Silent { yes: true };
    let targets = procedure::targets(false);
    let session = procedure::collect(&mut client, &mut hand, &targets, &options(), &mut feedback).unwrap();
    // Every target captured once, under its own name, with the board resting within that target's
    // tolerance (the reading's own offset, under 0.1 g, tilts it by at most 6 degrees more).
    let mut captured: Vec<&str> = session.captures.iter().map(|c| c.name.as_str()).collect();
    let mut wanted: Vec<&str> = targets.iter().map(|t| t.name.as_str()).collect();
    captured.sort();
    wanted.sort();
    assert_eq!(captured, wanted);
    for capture in &session.captures {
        let target = capture.target.as_ref().expect("each capture records its wanted orientation");
        assert_eq!(target.name, capture.name);
        let tilt = target.tilt_deg(capture.stats.mean_g.map(f64::from));
        assert!(tilt < target.tolerance_deg + 6.0, "{} captured {tilt:.1} degrees away", capture.name);
    }
    let outcome = session.outcome(shared::protocol::SensorConfig::default()).unwrap();
    assert_eq!(outcome.fit.model, accelcal::fit::Model::Ortho9);
    let calibration = outcome.calibration;
    client.set_calibration(calibration).unwrap();
    client.save_calibration().unwrap();
    drop(client);

    // Restart the board on the same flash, behind a new pseudo-terminal.
    let flash = pty.board.stop();
    let pty = pty_board(flash, 12);
    let port = open_serial(&pty.path, accelcal::link::port::DEFAULT_BAUD).unwrap();
    let (mut client, info) = Client::connect(Box::new(port) as Box<dyn Port>).unwrap();
    assert_eq!(info.active, ActiveCalibration::Stored);
    assert_eq!(client.calibration(CalibrationSlot::Active).unwrap(), Some(calibration));

    let mut hand = SimulatedHand::new(pty.board.controls(), PLACEMENT_DEG, 13);
    let verification = procedure::verify(&mut client, &mut hand, 12, WAIT, &mut feedback).unwrap();
    println!("default set over a pty: {verification:?}");
    assert!(verification.before_rms_mg >= 10.0, "{verification:?}");
    assert!(verification.after_rms_mg <= 1.0, "{verification:?}");
    // The noise floor of 5 s captures of 400 ug/sqrt(Hz) white noise: 0.4 mg / sqrt(2 * 5) = 0.126 mg
    // on each axis, and so in |a|; the floor is an RMS over 12 captures whose spreads each come from
    // thousands of samples: within 10 %.
    let expected_floor = 0.4 / (2.0 * f64::from(procedure::VERIFY_SECONDS)).sqrt();
    let floor = verification.noise_floor_mg;
    assert!((floor / expected_floor - 1.0).abs() < 0.1, "floor {floor} for {expected_floor}: {verification:?}");
    let without = (verification.after_rms_mg.powi(2) - floor.powi(2)).max(0.0).sqrt();
    assert!((verification.after_rms_without_noise_mg - without).abs() < 1e-12, "{verification:?}");
    // The chip's own corrected samples agree with the verified calibration (noise of 20 samples).
    assert!(verification.on_chip_difference_mg < 3.0, "{verification:?}");
}

#[test]
fn quick_on_the_chip_verifies_within_a_few_mg_with_no_fit_on_the_host() {
    // NOTE: the chip's ortho9 needs no exact placement; what verification still sees is its own
    // noise (0.13 mg) and the realistic sensor warming on after the calibration (about 1.4 mg/degC
    // on z): the calibration's own error against the truth is measured in tests/quick_mode.rs.
    let (mut before, mut after) = (0.0, 0.0);
    for seed in 1..=6 {
        let (host, device) = pipe();
        let board = SimBoard::spawn(device, SimFlash::new(), seed);
        let (mut client, _) = Client::connect(host).unwrap();
        let mut hand = SimulatedHand::new(board.controls(), PLACEMENT_DEG, seed);
        let mut feedback = Silent { yes: true };
        let quick = CollectOptions { seconds: procedure::capture_seconds(true), wait_limit: WAIT };
        procedure::collect(&mut client, &mut hand, &procedure::targets(true), &quick, &mut feedback).unwrap();
        let chip = client.fit_ortho9().unwrap();
        client.set_calibration(chip.calibration).unwrap();
        client.save_calibration().unwrap();
        let verification = procedure::verify(&mut client, &mut hand, 12, WAIT, &mut feedback).unwrap();
        println!(
            "quick, seed {seed}: {:.1} mg rms before, {:.3} mg after",
            verification.before_rms_mg, verification.after_rms_mg
        );
        before += verification.before_rms_mg / 6.0;
        after += verification.after_rms_mg / 6.0;
    }
    println!("quick, mean of six runs: {before:.1} mg rms before, {after:.3} mg after");
    assert!(after < 2.0, "quick: {before:.1} -> {after:.3} mg");
}

/// A feedback that remembers the live lines.
#[derive(Default)]
struct Recorder {
    live: Vec<String>,
}

impl Feedback for Recorder {
    fn say(&mut self, _: &str) {}
    fn live(&mut self, line: &str) {
        self.live.push(line.to_owned());
    }
    fn progress(&mut self, _: u32, _: u32) {}
    fn progress_done(&mut self) {}
    fn confirm(&mut self, _: &str) -> bool {
        true
    }
}

/// A hand that always rests the board on +X.
struct Stubborn(Sender<SimCommand>);

impl Hand for Stubborn {
    fn present(&mut self, _: &Orientation, _: &mut dyn Feedback) -> Result<(), ProcedureError> {
        let _ = self.0.send(SimCommand::Place([1.0, 0.0, 0.0]));
        Ok(())
    }
    fn fresh(&mut self, _: usize, _: &mut dyn Feedback) -> Result<(), ProcedureError> {
        Ok(())
    }
    fn turn_quarter(&mut self, _: &mut dyn Feedback) -> Result<(), ProcedureError> {
        Ok(())
    }
}

#[test]
fn a_repeated_position_is_refused_by_name_and_the_wait_ends_with_what_is_missing() {
    let (host, device) = pipe();
    let board = SimBoard::spawn(device, SimFlash::new(), 31);
    let (mut client, _) = Client::connect(host).unwrap();
    let targets = [Orientation::face(Position::PosX), Orientation::face(Position::NegX)];
    let mut recorder = Recorder::default();
    let options = CollectOptions { wait_limit: Some(Duration::from_secs(2)), ..options() };
    let error = procedure::collect(&mut client, &mut Stubborn(board.controls()), &targets, &options, &mut recorder)
        .unwrap_err()
        .to_string();
    assert!(recorder.live.iter().any(|l| l == "+X is already captured: turn the board to -X"), "{:?}", recorder.live);
    assert_eq!(error, "the board never came to rest at any of -X; place it and run the command again");
}

#[test]
fn a_board_moved_during_the_capture_is_named_with_what_to_do() {
    let (host, device) = pipe();
    let board = SimBoard::spawn(device, SimFlash::new(), 41);
    let (mut client, _) = Client::connect(host).unwrap();
    board.controls().send(SimCommand::Move(Motion::Rotating { axis: [1.0, 0.0, 0.0], rate_dps: 3.0 })).unwrap();
    let error = client.run(Request::Capture { seconds: 5 }, |_| {}).unwrap_err();
    assert!(matches!(error, LinkError::Device(DeviceError::Moved { .. })));
    let line = error.to_string();
    assert!(line.starts_with("the board moved during the capture (scatter "), "{line}");
    assert!(line.ends_with("rest it against something firm and keep still"), "{line}");
}

#[test]
fn a_missing_sensor_is_named_with_the_pins_to_check() {
    let (host, device) = pipe();
    let board = SimBoard::spawn(device, SimFlash::new(), 51);
    board.controls().send(SimCommand::Connect(false)).unwrap();
    let (mut client, _) = Client::connect(host).unwrap();
    let error = client.run(Request::Capture { seconds: 5 }, |_| {}).unwrap_err().to_string();
    assert_eq!(
        error,
        "the MPU-6050 does not answer at 0x68 or 0x69: check VCC, GND, SCL (PB6) and SDA (PB7) and the pull-ups"
    );
}

#[test]
fn a_port_that_vanishes_mid_capture_is_an_error_within_2_s_and_the_session_file_is_intact() {
    use accelcal::session::{CaptureRecord, Session};
    let (host, device) = pipe();
    let board = SimBoard::spawn(device, SimFlash::new(), 71);
    let (mut client, _) = Client::connect(host).unwrap();
    let Response::Captured { stats, .. } = client.run(Request::Capture { seconds: 5 }, |_| {}).unwrap() else {
        panic!("no capture")
    };
    let target = Orientation::named("+Z");
    let record = CaptureRecord { name: "+Z".into(), target, face: None, unix_time_s: 0.0, stats, closing: false };
    let session = Session { captures: vec![record], ..Session::default() };
    let stem = std::env::temp_dir().join(format!("accelcal-vanish-{}", std::process::id()));
    session.save(&stem).unwrap();
    let before = std::fs::read(stem.with_extension("json")).unwrap();

    let controls = board.controls();
    let started = std::time::Instant::now();
    let mut progress = 0;
    let error = client
        .run(Request::Capture { seconds: 20 }, |_| {
            progress += 1;
            if progress == 3 {
                let _ = controls.send(SimCommand::Stop); // the cable is pulled
            }
        })
        .unwrap_err();
    // The board's end of the link is gone: the client says so at once, not after a silence.
    assert!(matches!(error, LinkError::Disconnected { .. }), "{error}");
    // NOTE: a bound on a hang, not a timing measurement: the client gives up after SILENCE_LIMIT
    // (2 s) of silence at most; a dropped link is noticed at once. Generous for a loaded machine.
    let bound = accelcal::limits::SILENCE_LIMIT + Duration::from_secs(3);
    assert!(started.elapsed() < bound, "{:?}", started.elapsed());
    assert_eq!(std::fs::read(stem.with_extension("json")).unwrap(), before, "the session file changed");
    assert_eq!(Session::load(&stem.with_extension("json")).unwrap(), session);
}

#[test]
fn a_device_restarting_mid_capture_is_noticed_and_named() {
    let (host, device) = pipe();
    let board = SimBoard::spawn(device, SimFlash::new(), 72);
    let (mut client, _) = Client::connect(host).unwrap();
    let controls = board.controls();
    let mut progress = 0;
    let error = client
        .run(Request::Capture { seconds: 20 }, |_| {
            progress += 1;
            if progress == 2 {
                let _ = controls.send(SimCommand::Restart);
            }
        })
        .unwrap_err();
    assert_eq!(
        error.to_string(),
        "the device stopped answering in the middle of the operation: it restarted or lost power; \
         check the cable and the power, then run the command again"
    );
    // The rebooted board answers again.
    assert!(matches!(
        client.call(Request::Hello { protocol_version: shared::protocol::PROTOCOL_VERSION }),
        Ok(Response::Hello(_))
    ));
}

#[test]
fn verification_waits_for_a_new_orientation_instead_of_counting_one_twice() {
    let (host, device) = pipe();
    let board = SimBoard::spawn(device, SimFlash::new(), 81);
    let (mut client, _) = Client::connect(host).unwrap();
    let calibration = shared::Calibration::identity(shared::AccelRange::G2);
    client.call(Request::SetCalibration(calibration)).unwrap();
    let mut recorder = Recorder::default();
    let error =
        procedure::verify(&mut client, &mut Stubborn(board.controls()), 2, Some(Duration::from_secs(2)), &mut recorder)
            .unwrap_err()
            .to_string();
    assert!(recorder
        .live
        .iter()
        .any(|l| l == "this orientation was used already (to calibrate or verify): turn the board to a new one"));
    // What was verified before the board stopped coming to rest is said, not lost.
    assert!(
        error.starts_with(
            "the board never came to rest at a new orientation; turn it and hold it still, then run the command again; 1 of 2 orientations verified: "
        ),
        "{error}"
    );
}
