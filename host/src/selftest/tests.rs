use std::sync::mpsc::Sender;

use firmware::sim::part::{SimPart, FAULTY_AXIS_ERROR, SIM_PART_NAMES};

use super::*;
use crate::sim::{SimBoard, SimCommand, SimSensor};

/// A watcher that does nothing but count the moves it is told of.
#[derive(Default)]
struct Still {
    moves: Vec<u8>,
}

impl Watcher for Still {
    fn phase(&mut self, _: u8, _: PhaseName) {}
    fn moved(&mut self, attempt: u8, _: &str) {
        self.moves.push(attempt);
    }
}

fn part(name: &str) -> SimPart {
    SimPart::by_name(name).expect("a simulated part")
}

/// Runs the self-test on a fresh simulated board carrying `part`.
fn self_test(part: SimPart, watcher: &mut dyn Watcher) -> Result<SelfTest, SelfTestError> {
    let (mut connection, _board) = SimBoard::in_process_part((7, SimSensor::Realistic, part)).unwrap();
    run(&mut connection.client, &connection.info, watcher)
}

/// Each axis's deviation from its trim, in percent, as the simulated part was made.
fn made_deviation_percent(part: &SimPart) -> [f32; 6] {
    part.response_ratio.map(|ratio| (ratio - 1.0) * 100.0)
}

#[test]
fn every_healthy_simulated_part_passes_with_its_deviations_measured_within_half_a_percent() {
    for name in SIM_PART_NAMES {
        let part = part(name);
        let result = self_test(part, &mut Still::default());
        let test = result.unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(test.passed(), "{name}: {:?}", test.verdicts);
        assert_eq!(test.raw.codes, part.codes, "{name}");
        assert_eq!(test.raw.attempts, 1, "{name}");
        for (verdict, made) in test.verdicts.iter().zip(made_deviation_percent(&part)) {
            let measured = verdict.deviation_percent.expect("every simulated code is non-zero");
            assert!(
                (measured - made).abs() < 0.5,
                "{name} {}: {measured:.2} % measured, {made:.2} % made",
                verdict.axis
            );
        }
    }
}

#[test]
fn an_axis_20_percent_off_fails_on_every_family_and_the_others_pass() {
    for name in SIM_PART_NAMES {
        for axis in 0..3 {
            let result = self_test(part(name).with_faulty_axis(axis), &mut Still::default());
            let test = result.unwrap_or_else(|e| panic!("{name}: {e}"));
            assert!(!test.passed(), "{name} axis {axis}");
            for (i, verdict) in test.verdicts.iter().enumerate() {
                let faulty = i % 3 == axis;
                assert_eq!(verdict.passed, !faulty, "{name} faulty {axis}: {verdict:?}");
                if faulty {
                    let measured = verdict.deviation_percent.unwrap_or(f32::NAN);
                    assert!((measured - FAULTY_AXIS_ERROR * 100.0).abs() < 0.5, "{name} {}: {measured}", verdict.axis);
                }
            }
            // NOTE: the MPU-6500 family's own band lets a 20 %-off response pass.
            let datasheet = shared::selftest::datasheet_passed(&test.verdicts);
            assert_eq!(datasheet, part(name).family == Family::Mpu6500, "{name} axis {axis}");
        }
    }
}

/// A hand that tips the simulated board while the first attempt's self-test is on.
struct Bumping {
    controls: Sender<SimCommand>,
    moves: Vec<u8>,
}

impl Watcher for Bumping {
    fn phase(&mut self, attempt: u8, phase: PhaseName) {
        if attempt == 1 && phase == PhaseName::On {
            self.controls.send(SimCommand::Tip(30.0)).unwrap();
        }
    }
    fn moved(&mut self, attempt: u8, _: &str) {
        self.moves.push(attempt);
    }
}

#[test]
fn a_board_moved_during_the_first_attempt_is_retried_and_then_passes() {
    for name in ["mpu6050", "mpu6500"] {
        let (mut connection, board) = SimBoard::in_process_part((3, SimSensor::Realistic, part(name))).unwrap();
        let mut bumping = Bumping { controls: board.controls(), moves: Vec::new() };
        let test = run(&mut connection.client, &connection.info, &mut bumping).unwrap();
        assert_eq!((bumping.moves, test.raw.attempts), (vec![1], 2), "{name}");
        assert!(test.passed(), "{name}: {:?}", test.verdicts);
        let text = report::text(&test, None);
        assert!(text.contains("+-250 deg/s, 2 attempts (the board moved; repeated)\n"), "{name}: {text}");
    }
}

/// A hand that keeps shaking the board through every attempt.
struct Shaking(Sender<SimCommand>);

impl Watcher for Shaking {
    fn phase(&mut self, _: u8, _: PhaseName) {
        let motion = firmware::sim::physics::Motion::Vibrating { amplitude_g: 0.05, frequency_hz: 3.0 };
        self.0.send(SimCommand::MoveFor { motion, seconds: 0.5 }).unwrap();
    }
    fn moved(&mut self, _: u8, _: &str) {}
}

#[test]
fn a_board_that_keeps_moving_is_named_after_the_last_attempt() {
    let (mut connection, board) = SimBoard::in_process_part((3, SimSensor::Realistic, part("mpu6050"))).unwrap();
    let result = run(&mut connection.client, &connection.info, &mut Shaking(board.controls()));
    assert!(matches!(result, Err(SelfTestError::KeptMoving { attempts: SELF_TEST_ATTEMPTS })), "{result:?}");
}

#[test]
fn the_sensor_registers_and_the_board_configuration_are_as_before_after_the_self_test() {
    for name in ["mpu6050", "icm20689"] {
        let (mut connection, board) = SimBoard::in_process_part((5, SimSensor::Realistic, part(name))).unwrap();
        let client = &mut connection.client;
        // SMPLRT_DIV to ACCEL_CONFIG2 (0x19-0x1D), read as the datasheet numbers them.
        let before = client.read_registers(0x19, 5).unwrap();
        run(client, &connection.info, &mut Shaking(board.controls())).unwrap_err();
        run(client, &connection.info, &mut Still::default()).unwrap();
        assert_eq!(client.read_registers(0x19, 5).unwrap(), before, "{name}");
        assert_eq!(before[2..4], [0x10, 0x00], "{name}: +-1000 deg/s and +-2 g, no self-test bit");
        assert!(client.take_temperature_bins().unwrap().is_empty(), "{name}: the self-test's samples left no bin");
    }
}

/// Ctrl-C pressed while the first attempt's self-test is on.
struct Interrupting(std::sync::Arc<std::sync::atomic::AtomicBool>);

impl Watcher for Interrupting {
    fn phase(&mut self, _: u8, phase: PhaseName) {
        if phase == PhaseName::On {
            self.0.store(true, std::sync::atomic::Ordering::SeqCst);
        }
    }
    fn moved(&mut self, _: u8, _: &str) {}
}

#[test]
fn ctrl_c_during_the_self_test_ends_it_as_interrupted_with_the_configuration_written_back() {
    let (mut connection, _board) = SimBoard::in_process_part((6, SimSensor::Realistic, part("mpu9250"))).unwrap();
    let client = &mut connection.client;
    let before = client.read_registers(0x19, 5).unwrap();
    let flag = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
    client.interrupt_on(flag.clone());
    let result = run(client, &connection.info, &mut Interrupting(flag.clone()));
    assert!(matches!(result, Err(SelfTestError::Link(LinkError::Interrupted))), "{result:?}");
    client.take_interrupt();
    assert_eq!(client.read_registers(0x19, 5).unwrap(), before);
}

#[test]
fn the_text_shows_the_previous_deviation_beside_each_axis_and_the_family_verdict_beside_accelcals() {
    let test = self_test(part("mpu6500").with_faulty_axis(0), &mut Still::default()).unwrap();
    let axes: Vec<_> = (0..6).map(|i| serde_json::json!({ "deviation_percent": 1.5 + i as f64 })).collect();
    let previous =
        history::HistoryEntry { date_utc: "2026-11-24 10:00".into(), result: serde_json::json!({ "axes": axes }) };
    let text = report::text(&test, Some(&previous));
    let line = |axis: &str| text.lines().find(|l| l.starts_with(axis)).unwrap_or_default().to_owned();
    assert!(text.contains("previous (2026-11-24 10:00)"), "{text}");
    assert!(text.contains("+-250 deg/s, 1 attempt\n"), "{text}");
    assert!(line("accel_x").contains("FAIL") && line("accel_x").ends_with("+1.5 %"), "{text}");
    assert!(line("gyro_z").contains("pass") && line("gyro_z").ends_with("+6.5 %"), "{text}");
    let verdict = text.lines().last().unwrap_or_default();
    assert!(verdict.starts_with("FAILED: accel_x, gyro_x outside +-14 %") && verdict.ends_with("it passes"), "{text}");
}

#[test]
fn the_board_keeps_the_latest_self_test_and_its_next_hello_carries_it_with_the_same_verdicts() {
    use shared::selftest::StoredSelfTest;
    let faulty = (7, SimSensor::Realistic, part("mpu6500").with_faulty_axis(1));
    let (mut connection, _board) = SimBoard::in_process_part(faulty).unwrap();
    assert_eq!(crate::session::BoardRecord::of(&connection.info).self_test, None, "a fresh board has none");
    let test = run(&mut connection.client, &connection.info, &mut Still::default()).unwrap();
    // 2026-11-25 05:00 UTC.
    let stored = StoredSelfTest { unix_time_s: 1_795_582_800, raw: test.raw };
    connection.client.store_self_test(&stored).unwrap();
    let info = connection.client.hello().unwrap();
    let kept = crate::session::BoardRecord::of(&info).self_test.expect("the board keeps it");
    assert_eq!(kept.date_utc, "2026-11-25 05:00");
    assert_eq!(kept.result["part"], "MPU-6500");
    assert_eq!(kept.result["passed"], false, "the faulty y axis failed");
    for (axis, verdict) in test.verdicts.iter().enumerate() {
        let (board, run) = (kept.deviation_percent(axis).unwrap(), verdict.deviation_percent.unwrap());
        assert!((board - run).abs() < 1e-4, "{}: {board} on the board, {run} measured", verdict.axis);
    }
}
