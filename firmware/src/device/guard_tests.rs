//! The guards of the device, each against the case it exists for: a calibrated stream at another
//! range, stream decimation, an implausible on-chip fit, register access during a stream, and the
//! stored self-test.

use shared::protocol::{DeviceError, Request, Response, SensorConfig, StreamKind, PROTOCOL_VERSION};
use shared::selftest::SelfTestRecord;
use shared::{AccelRange, Calibration, CalibrationError, Position};

use embassy_futures::block_on;

use super::tests::{ask, boot, capture_at, drain, run, Flash, SimDevice};
use crate::sim::SimMpu6050;

fn samples(device: &mut SimDevice, kind: StreamKind, rate_hz: u16, count: u32) -> Vec<shared::protocol::Sample> {
    let (last, streamed) = run(device, 2, Request::Stream { kind, rate_hz, count });
    assert_eq!(last, Response::StreamEnded { samples: count, dropped: 0 });
    streamed.into_iter().filter_map(|r| if let Response::Sample(s) = r { Some(s) } else { None }).collect()
}

#[test]
fn a_calibrated_stream_at_another_range_than_the_calibration_is_refused_and_a_raw_one_is_not() {
    let mut device = boot(SimMpu6050::new(21), Flash::new());
    let calibration = Calibration { offset_g: [0.02, 0.0, 0.0], ..Calibration::identity(AccelRange::G2) };
    assert_eq!(ask(&mut device, 1, Request::SetCalibration(calibration)), Response::Done);
    let wider = SensorConfig { range: AccelRange::G8, ..SensorConfig::default() };
    assert!(matches!(ask(&mut device, 1, Request::Configure(wider)), Response::Configured(_)));
    let stream = Request::Stream { kind: StreamKind::Calibrated, rate_hz: 50, count: 5 };
    assert_eq!(
        ask(&mut device, 3, stream),
        Response::Error(DeviceError::RangeMismatch { calibration: AccelRange::G2, configured: AccelRange::G8 })
    );
    assert!(!device.is_busy(), "the refused stream must not have started");
    assert_eq!(samples(&mut device, StreamKind::Raw, 50, 5).len(), 5);
}

#[test]
fn a_decimated_stream_sends_exactly_count_samples_every_nth_of_the_sensor_s() {
    // Two boards with the same seed produce the same samples at the same simulated times, so the
    // 25 Hz stream must be exactly every 4th sample of the 100 Hz one, starting with the first.
    let mut full_rate = boot(SimMpu6050::new(22), Flash::new());
    let mut decimated = boot(SimMpu6050::new(22), Flash::new());
    let every = samples(&mut full_rate, StreamKind::Raw, 100, 120);
    let quarter = samples(&mut decimated, StreamKind::Raw, 25, 30);
    assert_eq!(quarter.len(), 30);
    for (k, sample) in quarter.iter().enumerate() {
        assert_eq!(sample.index, k as u32);
        let source = &every[4 * k];
        assert_eq!((sample.accel_g, sample.gyro_dps), (source.accel_g, source.gyro_dps), "sample {k}");
    }
}

#[test]
fn an_absurd_six_position_fit_is_refused_with_the_reason_and_the_active_calibration_is_kept() {
    let mut sim = SimMpu6050::new(23);
    // A sensor whose x axis picks up 0.3 of y: the correction's cross-axis term would be 0.3, beyond
    // the limit. (An absurd scale cannot reach the fit: a reading that far from 1 g is no face.)
    sim.physics.truth.matrix[0][1] = 0.3;
    let mut device = boot(sim, Flash::new());
    let kept = Calibration { offset_g: [0.01, 0.0, 0.0], ..Calibration::identity(AccelRange::G2) };
    assert_eq!(ask(&mut device, 1, Request::SetCalibration(kept)), Response::Done);
    for position in Position::ALL {
        let answer = capture_at(&mut device, position.specific_force_g());
        assert!(matches!(answer, Response::Captured { position: Some(p), .. } if p == position), "{answer:?}");
    }
    let answer = ask(&mut device, 8, Request::FitSixPosition);
    let Response::Error(DeviceError::InvalidCalibration(CalibrationError::CrossAxisOutOfRange {
        row: 0,
        col: 1,
        value,
    })) = answer
    else {
        panic!("expected the xy cross-axis term refused, got {answer:?}")
    };
    assert!((value - 0.3).abs() < 0.01, "fitted xy term {value}");
    assert_eq!(device.active_calibration(), Some(kept));
}

#[test]
fn a_reading_far_from_1_g_is_no_face_however_it_points() {
    // A sensor returning (nearly) zeros, or at a wrong range, points along some axis all the same.
    for (mean_g, face) in [
        ([0.0, 0.0, 0.002], None),
        ([0.001, -0.0005, 0.0], None),
        ([0.0, 0.0, 0.5], None),
        ([0.0, 0.0, 2.0], None),
        ([0.0, 0.0, 0.76], Some(Position::PosZ)),
        ([0.0, -1.2, 0.0], Some(Position::NegY)),
    ] {
        assert_eq!(super::jobs::face_of(mean_g), face, "{mean_g:?}");
    }
    assert!(shared::protocol::reads_gravity(1.0 - shared::protocol::MAX_GRAVITY_ERROR_G));
    assert!(!shared::protocol::reads_gravity(1.0 - 1.01 * shared::protocol::MAX_GRAVITY_ERROR_G));
}

#[test]
fn register_access_is_refused_while_a_stream_runs_and_every_hello_writes_the_configuration_again() {
    let mut device = boot(SimMpu6050::new(24), Flash::new());
    let read = |register| Request::Register { register, write: None };
    // GYRO_CONFIG (0x1B) and ACCEL_CONFIG (0x1C) as the board configures them: +-1000 deg/s, +-2 g.
    assert_eq!(ask(&mut device, 1, read(0x1B)), Response::Register(0x10));
    assert_eq!(ask(&mut device, 1, read(0x1C)), Response::Register(0x00));
    assert_eq!(ask(&mut device, 1, read(0x75)), Response::Register(0x68));
    block_on(device.handle(2, Request::Stream { kind: StreamKind::Raw, rate_hz: 100, count: 0 }));
    let busy = Response::Error(DeviceError::Busy);
    assert_eq!(ask(&mut device, 3, Request::Register { register: 0x1B, write: Some(0xE0) }), busy);
    assert_eq!(ask(&mut device, 4, read(0x1B)), busy);
    block_on(device.handle(5, Request::Cancel));
    drain(&mut device);
    // Self-test on at +-250 deg/s and +-8 g, as the self-test writes it, read back in the answer.
    for (register, value) in [(0x1B, 0xE0), (0x1C, 0xF0)] {
        let answer = ask(&mut device, 6, Request::Register { register, write: Some(value) });
        assert_eq!(answer, Response::Register(value));
    }
    let hello = ask(&mut device, 8, Request::Hello { protocol_version: shared::protocol::PROTOCOL_VERSION });
    assert!(matches!(hello, Response::Hello(_)), "{hello:?}");
    assert_eq!(ask(&mut device, 9, read(0x1B)), Response::Register(0x10));
    assert_eq!(ask(&mut device, 9, read(0x1C)), Response::Register(0x00));
}

#[test]
fn a_stored_self_test_is_in_every_hello_after_a_reboot_and_a_calibration_erase_leaves_it() {
    let hello = |device: &mut SimDevice| match ask(device, 1, Request::Hello { protocol_version: PROTOCOL_VERSION }) {
        Response::Hello(info) => info.self_test,
        other => panic!("{other:?}"),
    };
    let mut device = boot(SimMpu6050::new(25), Flash::new());
    assert_eq!(hello(&mut device), None, "a fresh board has none");
    let record = SelfTestRecord::from_slice(&[0x9A, 0x01, 0x02, 0x03]).unwrap();
    block_on(device.handle(2, Request::Stream { kind: StreamKind::Raw, rate_hz: 100, count: 0 }));
    assert_eq!(ask(&mut device, 3, Request::StoreSelfTest(record.clone())), Response::Error(DeviceError::Busy));
    block_on(device.handle(4, Request::Cancel));
    drain(&mut device);
    assert_eq!(hello(&mut device), None, "nothing was stored while busy");
    assert_eq!(ask(&mut device, 5, Request::StoreSelfTest(record.clone())), Response::Done);
    assert_eq!(hello(&mut device), Some(record.clone()));
    assert_eq!(ask(&mut device, 6, Request::EraseCalibration), Response::Done);
    let (sim, flash) = device.into_parts();
    let mut device = boot(sim, flash);
    assert_eq!(hello(&mut device), Some(record), "kept across the erase and the reboot, byte for byte");
}
