//! The family confirmed by its offset registers, on every simulated part.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use firmware::sim::part::{SimPart, SIM_PART_NAMES};
use shared::part::Family;
use shared::protocol::SensorIdentity;

use super::{check_family, FamilyCheck, Verdict};
use crate::link::{Connection, LinkError};
use crate::part::offsets::{Measured, OffsetCheckError, OffsetStep};
use crate::sim::{SimBoard, SimSensor};

/// Both families' accelerometer offset registers as the maps number them: 0x06-0x0B, 0x77-0x7E.
fn offset_registers(connection: &mut Connection) -> Vec<u8> {
    let client = &mut connection.client;
    [client.read_registers(0x06, 6).unwrap(), client.read_registers(0x77, 8).unwrap()].concat()
}

/// The check on a fresh realistic simulated board carrying `part`, with the offset registers before
/// and after it.
fn checked(part: SimPart, seed: u64) -> (FamilyCheck, Vec<u8>, Vec<u8>) {
    let (mut connection, _board) = SimBoard::in_process_part((seed, SimSensor::Realistic, part)).unwrap();
    let before = offset_registers(&mut connection);
    let (info, client) = (connection.info.clone(), &mut connection.client);
    let check = check_family(client, &info.sensor.unwrap(), info.config).unwrap();
    (check, before, offset_registers(&mut connection))
}

#[test]
fn every_simulated_part_is_confirmed_by_its_offset_registers_which_are_restored() {
    for (seed, name) in SIM_PART_NAMES.iter().enumerate() {
        let part = SimPart::by_name(name).unwrap();
        let (check, before, after) = checked(part, 20 + seed as u64);
        assert_eq!((check.verdict, check.confirmed_by()), (Verdict::Confirmed, Some("offset registers")), "{name}");
        assert_eq!((check.family, check.attempts), (part.family, 1), "{name}");
        // Registers 0x06 (MPU-6050) and 0x77 (MPU-6500 family): the own family's moves x by its step
        // of 125 mg, the other's leaves it within the noise of a mean (well below 5 mg).
        let own = if part.family == Family::Mpu6050 { 0x06 } else { 0x77 };
        for step in &check.steps {
            assert!((step.expected_g.abs() - 0.125).abs() < 1e-9, "{name}: {step:?}");
            let wanted_g = if step.register == own { step.expected_g } else { 0.0 };
            assert!((step.moved_g - wanted_g).abs() < 0.005, "{name}: {step:?}");
        }
        assert_eq!(after, before, "{name}: the offset registers were not restored");
    }
}

#[test]
fn a_6500_family_map_answering_0x68_is_confirmed_as_its_family_and_named_not_the_part_it_claims() {
    let (check, before, after) = checked(SimPart { who_am_i: 0x68, ..SimPart::mpu6500() }, 31);
    assert_eq!(check.verdict, Verdict::ContradictsWhoAmI { claimed: Family::Mpu6050 });
    assert_eq!(check.family, Family::Mpu6500);
    let summary = check.summary();
    assert!(summary.contains("not the MPU-6050 family its WHO_AM_I claims"), "{summary}");
    assert_eq!(after, before);
}

#[test]
fn a_part_that_ignores_its_offset_registers_is_not_confirmed() {
    for (seed, part) in [SimPart::mpu6050(), SimPart::mpu6500(), SimPart::icm20689()].into_iter().enumerate() {
        let (check, before, after) = checked(part.ignoring_offsets(), 40 + seed as u64);
        assert_eq!((check.verdict, check.confirmed_by()), (Verdict::OffsetsIgnored, None), "{part:?}");
        assert!(check.steps.iter().all(|step| step.moved_g.abs() < 0.005), "{:?}", check.steps);
        assert!(check.summary().starts_with("NOT confirmed: neither"), "{}", check.summary());
        assert_eq!(after, before);
    }
}

#[test]
fn ctrl_c_during_the_check_ends_it_as_interrupted_with_the_offsets_written_back() {
    let (mut connection, board) = SimBoard::in_process_part((50, SimSensor::Realistic, SimPart::mpu6500())).unwrap();
    let before = offset_registers(&mut connection);
    let flag = Arc::new(AtomicBool::new(false));
    connection.client.interrupt_on(flag.clone());
    // NOTE: the first step's phase runs from about 0.45 s to 0.9 s after the check starts (a baseline of
    // 0.45 s first); time on the simulated board passes only while it streams.
    let (clock, start_s, pressed) = (board.clock(), board.clock()(), flag.clone());
    let presser = std::thread::spawn(move || {
        while clock() < start_s + 0.6 {
            std::thread::sleep(std::time::Duration::from_micros(50));
        }
        pressed.store(true, Ordering::SeqCst);
    });
    let (info, client) = (connection.info.clone(), &mut connection.client);
    let result = check_family(client, &info.sensor.unwrap(), info.config);
    presser.join().unwrap();
    assert!(matches!(result, Err(OffsetCheckError::Link(LinkError::Interrupted))), "{result:?}");
    connection.client.take_interrupt();
    assert_eq!(offset_registers(&mut connection), before);
}

/// A check as `judge` sees it: steps of `moved_mg` at 0x06 and 0x77, each 125 mg expected.
fn judged(who_am_i: u8, family: Family, moved_mg: [f64; 2]) -> Verdict {
    judged_check(who_am_i, family, moved_mg).verdict
}

/// The whole check of [`judged`].
fn judged_check(who_am_i: u8, family: Family, moved_mg: [f64; 2]) -> FamilyCheck {
    let step = |i: usize, family, register| OffsetStep {
        family,
        register,
        kept: true,
        expected_g: 0.125,
        moved_g: moved_mg[i] * 1e-3,
    };
    let steps = [step(0, Family::Mpu6050, 0x06), step(1, Family::Mpu6500, 0x77)];
    let identity = SensorIdentity { address: 0x68, who_am_i, family };
    FamilyCheck::judge(&identity, Measured::Steps { steps, attempts: 1 })
}

#[test]
fn the_verdict_names_which_register_moved_the_output_against_the_read_back_and_the_who_am_i() {
    use Family::{Mpu6050, Mpu6500};
    assert_eq!(judged(0x70, Mpu6500, [1.0, 124.0]), Verdict::Confirmed);
    assert_eq!(judged(0x68, Mpu6050, [126.0, -2.0]), Verdict::Confirmed);
    assert_eq!(judged(0x72, Mpu6050, [126.0, -2.0]), Verdict::Confirmed, "an unknown part claims nothing");
    assert_eq!(judged(0x68, Mpu6500, [0.0, 125.0]), Verdict::ContradictsWhoAmI { claimed: Mpu6050 });
    assert_eq!(judged(0x70, Mpu6500, [125.0, 0.0]), Verdict::ContradictsReadBack { by_offsets: Mpu6050 });
    assert_eq!(judged(0x70, Mpu6500, [3.0, -3.0]), Verdict::OffsetsIgnored);
    assert_eq!(judged(0x70, Mpu6500, [125.0, 125.0]), Verdict::Unclear, "both moved it");
    assert_eq!(judged(0x70, Mpu6500, [0.0, 250.0]), Verdict::Unclear, "twice the step");
    assert_eq!(judged(0x70, Mpu6500, [0.0, -125.0]), Verdict::Unclear, "the step's opposite");
    // The margin: 20 % of the step, 25 mg.
    assert_eq!(judged(0x70, Mpu6500, [24.0, 101.0]), Verdict::Confirmed);
    assert_eq!(judged(0x70, Mpu6500, [26.0, 125.0]), Verdict::Unclear);
    assert_eq!(judged(0x70, Mpu6500, [0.0, 99.0]), Verdict::Unclear);
}

// NOTE: the look-alikes the check exists for: a 6500-family map answering the MPU-6050's 0x68. Its
// offsets confirm the family the board runs it as, so calibration, info and selftest may rely on it.
#[test]
fn a_look_alike_whose_offsets_confirm_the_family_it_runs_as_is_confirmed_whatever_its_who_am_i() {
    let check = judged_check(0x68, Family::Mpu6500, [0.0, 125.0]);
    assert_eq!((check.confirmed(), check.confirmed_by()), (true, Some("offset registers")));
    let json = super::FamilyCheckJson::of(&check);
    assert_eq!((json.verdict, json.confirmed), ("contradicts_who_am_i", true));
    let read_back_wrong = judged_check(0x70, Family::Mpu6500, [125.0, 0.0]);
    assert_eq!((read_back_wrong.confirmed(), read_back_wrong.confirmed_by()), (false, None));
}

#[test]
fn a_board_that_keeps_moving_is_not_checked_and_says_so() {
    let identity = SensorIdentity { address: 0x68, who_am_i: 0x70, family: Family::Mpu6500 };
    let why = "the output scattered by 40.0 mg and 3.00 deg/s".to_owned();
    let check = FamilyCheck::judge(&identity, Measured::KeptMoving { attempts: 3, why });
    assert_eq!((check.verdict, check.confirmed_by()), (Verdict::BoardMoved, None));
    assert!(check.summary().starts_with("not checked: the board moved during each of 3 attempts"));
}

#[test]
fn a_check_whose_samples_are_lost_cannot_measure_and_says_it_left_the_offsets_as_found() {
    let (mut connection, board) = SimBoard::in_process_part((5, SimSensor::Realistic, SimPart::mpu6050())).unwrap();
    let before = offset_registers(&mut connection);
    board.controls().send(crate::sim::SimCommand::LoseSamples(1_000_000)).unwrap();
    let (info, client) = (connection.info.clone(), &mut connection.client);
    let error = check_family(client, &info.sensor.unwrap(), info.config).unwrap_err();
    assert!(matches!(error, OffsetCheckError::Stream(_)), "{error:?}");
    assert!(error.left_registers_as_found(), "{error}");
    assert!(error.to_string().contains("check the cable"), "{error}");
    assert_eq!(offset_registers(&mut connection), before);
    let interrupted = OffsetCheckError::Link(LinkError::Interrupted);
    assert!(!interrupted.left_registers_as_found(), "a link error may have cut a restore short");
}
