//! The device on the simulated MPU-6050 and RAM flash, request by request as the host drives it.

use embassy_futures::block_on;
use shared::calibration::{GyroCalibration, ModelTag, Origin, Procedure};
use shared::linalg;
use shared::protocol::{
    ActiveCalibration, CalibrationSlot, CaptureGoal, DeviceError, Request, Response, StreamKind, PROTOCOL_VERSION,
};
use shared::{AccelRange, Calibration, CalibrationError, Position, SixPositionError};

use super::Device;
use crate::sim::flash::RamFlash;
use crate::sim::physics::Motion;
use crate::sim::{sim_serial_number, SimMpu6050};

pub(super) type Flash = RamFlash<2048, 4>;
pub(super) type SimDevice = Device<SimMpu6050, Flash>;

/// Board loop period in the simulation, in microseconds.
const TICK_US: u64 = 20_000;

pub(super) fn boot(sim: SimMpu6050, flash: Flash) -> SimDevice {
    block_on(Device::boot(sim, flash, 0..4 * 2048, sim_serial_number(0))).expect("boots")
}

pub(super) fn drain(device: &mut SimDevice) -> Vec<(u16, Response)> {
    std::iter::from_fn(|| device.next_response()).collect()
}

/// One request with an instant answer: exactly one response, for that request.
pub(super) fn ask(device: &mut SimDevice, id: u16, request: Request) -> Response {
    block_on(device.handle(id, request));
    let mut responses = drain(device);
    assert_eq!(responses.len(), 1, "{responses:?}");
    let (answer_id, response) = responses.remove(0);
    assert_eq!(answer_id, id);
    response
}

/// Runs a long request to its final response; returns it and the progress messages before it.
pub(super) fn run(device: &mut SimDevice, id: u16, request: Request) -> (Response, Vec<Response>) {
    block_on(device.handle(id, request));
    let mut progress = Vec::new();
    for _ in 0..100_000 {
        for (answer_id, response) in drain(device) {
            assert_eq!(answer_id, id);
            match response {
                Response::Progress(_) | Response::Sample(_) => progress.push(response),
                last => return (last, progress),
            }
        }
        device.bus_mut().advance_us(TICK_US);
        block_on(device.poll());
    }
    panic!("no final response");
}

pub(super) fn capture_at(device: &mut SimDevice, up: [f32; 3]) -> Response {
    device.bus_mut().place(up);
    run(device, 7, Request::Capture { seconds: 10 }).0
}

#[test]
fn hello_names_the_sensor_and_refuses_another_protocol_version() {
    let mut device = boot(SimMpu6050::new(1), Flash::new());
    let Response::Hello(info) = ask(&mut device, 1, Request::Hello { protocol_version: PROTOCOL_VERSION }) else {
        panic!("no hello")
    };
    assert_eq!(info.sensor.unwrap().address, 0x68);
    assert_eq!(info.active, ActiveCalibration::None);
    assert!(!info.stored);
    let answer = ask(&mut device, 2, Request::Hello { protocol_version: PROTOCOL_VERSION + 1 });
    assert_eq!(
        answer,
        Response::Error(DeviceError::UnsupportedVersion { device: PROTOCOL_VERSION, host: PROTOCOL_VERSION + 1 })
    );
}

#[test]
fn a_capture_reports_progress_every_second_then_one_final_result_with_its_position() {
    let mut device = boot(SimMpu6050::new(2), Flash::new());
    device.bus_mut().place([0.0, -1.0, 0.0]);
    let (last, progress) = run(&mut device, 9, Request::Capture { seconds: 10 });
    // One progress message per second of data (at 1 s ... 9 s), then the result at 10 s.
    let seconds: Vec<u32> =
        progress.iter().map(|p| if let Response::Progress(p) = p { p.samples / 100 } else { 0 }).collect();
    assert_eq!(seconds, (1..=9).collect::<Vec<_>>());
    let Response::Captured { stats, position } = last else { panic!("{last:?}") };
    assert_eq!(position, Some(Position::NegY));
    assert_eq!(stats.samples, 1000);
}

#[test]
fn a_capture_until_its_mean_is_known_stops_where_the_sensor_noise_says() {
    // NOTE: the settled sensor's white noise, 400 ug/sqrt(Hz) at 100 Hz: 2.83 mg per sample, so a
    // mean known to 0.2 mg needs (2.83 / 0.2)^2 = 200 samples, within the scatter's own uncertainty.
    let mut device = boot(SimMpu6050::settled(6), Flash::new());
    device.bus_mut().place([0.0, 0.0, 1.0]);
    let goal = CaptureGoal { mean_std_g: 0.2e-3, min_samples: 50, max_samples: 2000 };
    let (last, _) = run(&mut device, 9, Request::CaptureUntil(goal));
    let Response::Captured { stats, position } = last else { panic!("{last:?}") };
    assert_eq!(position, Some(Position::PosZ));
    assert!((170..=235).contains(&stats.samples), "{} samples", stats.samples);
    let known = stats.std_g.iter().fold(0.0f32, |m, s| m.max(*s)) / (stats.samples as f32).sqrt();
    assert!(known <= 0.2e-3, "mean known to {known} g");
    let refused = CaptureGoal { max_samples: 2001, ..goal };
    let answer = ask(&mut device, 10, Request::CaptureUntil(refused));
    assert_eq!(answer, Response::Error(DeviceError::InvalidGoal));
}

#[test]
fn the_on_chip_six_position_fit_recovers_the_true_error_model() {
    // NOTE: a sub-mg claim about the fit needs one temperature: the settled static sensor.
    let mut device = boot(SimMpu6050::settled(3), Flash::new());
    let truth = device.bus_mut().physics.truth;
    let before = device.active_calibration();
    for position in Position::ALL {
        let answer = capture_at(&mut device, position.specific_force_g());
        assert!(matches!(answer, Response::Captured { position: Some(p), .. } if p == position), "{answer:?}");
    }
    let Response::Fitted(calibration) = ask(&mut device, 8, Request::FitSixPosition) else { panic!("no fit") };
    for axis in 0..3 {
        let offset_error_mg = (calibration.offset_g[axis] - truth.offset_g[axis]).abs() * 1000.0;
        assert!(offset_error_mg < 0.5, "offset {axis} off by {offset_error_mg} mg");
        let bias_error = (calibration.gyro.bias_dps[axis] - truth.gyro_bias_dps[axis]).abs();
        assert!(bias_error < 0.01, "gyro bias {axis} off by {bias_error} deg/s");
    }
    let matrix_error = linalg::max_abs_diff(&calibration.matrix, &truth.matrix);
    assert!(matrix_error < 1e-3, "M off by {matrix_error}");
    println!(
        "on-chip six-position, 10 s captures: |dM| max {matrix_error:.2e}, residual {} mg",
        calibration.residual_mg
    );
    // The fit is returned, not made active: only an upload changes the active calibration.
    assert_eq!(device.active_calibration(), before);
    assert_ne!(before, Some(calibration));
}

#[test]
fn the_fit_names_the_missing_position() {
    let mut device = boot(SimMpu6050::new(4), Flash::new());
    for position in [Position::PosX, Position::NegX, Position::PosY, Position::NegY, Position::PosZ] {
        capture_at(&mut device, position.specific_force_g());
    }
    assert_eq!(
        ask(&mut device, 3, Request::FitSixPosition),
        Response::Error(DeviceError::SixPosition(SixPositionError::Missing(Position::NegZ)))
    );
}

#[test]
fn a_second_long_operation_is_refused_and_cancel_ends_the_first() {
    let mut device = boot(SimMpu6050::new(5), Flash::new());
    block_on(device.handle(1, Request::Capture { seconds: 10 }));
    assert!(drain(&mut device).is_empty());
    assert_eq!(ask(&mut device, 2, Request::Capture { seconds: 10 }), Response::Error(DeviceError::Busy));
    assert_eq!(ask(&mut device, 3, Request::SaveCalibration), Response::Error(DeviceError::Busy));
    block_on(device.handle(4, Request::Cancel));
    assert_eq!(drain(&mut device), [(1, Response::Error(DeviceError::Cancelled)), (4, Response::Done)]);
    assert!(!device.is_busy());
}

#[test]
fn a_moved_board_is_reported_and_nothing_is_kept() {
    let mut device = boot(SimMpu6050::new(6), Flash::new());
    device.bus_mut().set_motion(Motion::Rotating { axis: [0.0, 1.0, 0.0], rate_dps: 2.0 });
    let (last, _) = run(&mut device, 1, Request::Capture { seconds: 5 });
    assert!(matches!(last, Response::Error(DeviceError::Moved { .. })), "{last:?}");
    let Response::Hello(info) = ask(&mut device, 2, Request::Hello { protocol_version: PROTOCOL_VERSION }) else {
        panic!()
    };
    assert_eq!(info.positions.present().count(), 0);
}

#[test]
fn a_saved_calibration_is_active_again_after_a_reboot() {
    let mut device = boot(SimMpu6050::new(7), Flash::new());
    let origin = Origin { procedure: Procedure::HostFit, model: ModelTag::new("ortho9").unwrap() };
    let calibration = Calibration { offset_g: [0.02, -0.01, 0.05], origin, ..Calibration::identity(AccelRange::G2) };
    assert_eq!(ask(&mut device, 1, Request::SetCalibration(calibration)), Response::Done);
    assert_eq!(ask(&mut device, 2, Request::SaveCalibration), Response::Done);
    let (sim, flash) = device.into_parts();
    let mut device = boot(sim, flash);
    assert_eq!(device.active_calibration(), Some(calibration));
    assert_eq!(
        ask(&mut device, 3, Request::GetCalibration(CalibrationSlot::Stored)),
        Response::Calibration(Some(calibration))
    );
    assert_eq!(ask(&mut device, 4, Request::EraseCalibration), Response::Done);
    let (sim, flash) = device.into_parts();
    assert_eq!(boot(sim, flash).active_calibration(), None);
}

#[test]
fn an_absurd_upload_is_refused_with_the_reason_and_changes_nothing() {
    let mut device = boot(SimMpu6050::new(8), Flash::new());
    let mut absurd = Calibration::identity(AccelRange::G2);
    absurd.matrix[1][1] = f32::NAN;
    assert_eq!(
        ask(&mut device, 1, Request::SetCalibration(absurd)),
        Response::Error(DeviceError::InvalidCalibration(CalibrationError::NonFinite))
    );
    let other_range = Calibration::identity(AccelRange::G8);
    assert_eq!(
        ask(&mut device, 2, Request::SetCalibration(other_range)),
        Response::Error(DeviceError::RangeMismatch { calibration: AccelRange::G8, configured: AccelRange::G2 })
    );
    assert_eq!(device.active_calibration(), None);
    assert_eq!(ask(&mut device, 3, Request::SaveCalibration), Response::Error(DeviceError::NoCalibration));
}

#[test]
fn streamed_samples_are_corrected_on_the_chip() {
    // NOTE: the settled static sensor, so that the truth holds at the temperature streamed at.
    let mut sim = SimMpu6050::settled(9);
    sim.place([0.0, 0.0, -1.0]);
    let truth = sim.physics.truth;
    let mut device = boot(sim, Flash::new());
    let calibration = Calibration {
        matrix: truth.matrix,
        offset_g: truth.offset_g,
        gyro: GyroCalibration { bias_dps: truth.gyro_bias_dps, ..GyroCalibration::default() },
        ..Calibration::identity(AccelRange::G2)
    };
    ask(&mut device, 1, Request::SetCalibration(calibration));
    let mean_z = |device: &mut SimDevice, kind| {
        let (last, samples) = run(device, 2, Request::Stream { kind, rate_hz: 50, count: 200 });
        assert_eq!(last, Response::StreamEnded { samples: 200, dropped: 0 });
        assert_eq!(samples.len(), 200);
        let z: f32 = samples.iter().map(|s| if let Response::Sample(s) = s { s.accel_g[2] } else { 0.0 }).sum();
        z / 200.0
    };
    let raw = mean_z(&mut device, StreamKind::Raw);
    let corrected = mean_z(&mut device, StreamKind::Calibrated);
    // Raw z reads -1 / 0.9834 - 0.078 = -1.095 g; corrected, -1 g within the noise of 200 samples.
    assert!((raw + 1.095).abs() < 0.003, "raw {raw}");
    assert!((corrected + 1.0).abs() < 0.001, "corrected {corrected}");
}

#[test]
fn a_missing_sensor_is_named_and_found_again_when_it_comes_back() {
    let mut sim = SimMpu6050::new(10);
    sim.set_connected(false);
    let mut device = boot(sim, Flash::new());
    let Response::Hello(info) = ask(&mut device, 1, Request::Hello { protocol_version: PROTOCOL_VERSION }) else {
        panic!()
    };
    assert_eq!(info.sensor, Err(DeviceError::SensorMissing));
    assert_eq!(ask(&mut device, 2, Request::Capture { seconds: 5 }), Response::Error(DeviceError::SensorMissing));
    device.bus_mut().set_connected(true);
    let (last, _) = run(&mut device, 3, Request::Capture { seconds: 5 });
    assert!(matches!(last, Response::Captured { .. }), "{last:?}");
}

#[test]
fn a_bus_error_during_a_capture_is_named_and_the_next_capture_works() {
    let mut device = boot(SimMpu6050::new(11), Flash::new());
    block_on(device.handle(1, Request::Capture { seconds: 5 }));
    device.bus_mut().advance_us(TICK_US);
    device.bus_mut().fail_next_transactions(1);
    block_on(device.poll());
    assert_eq!(drain(&mut device), [(1, Response::Error(DeviceError::Bus))]);
    let (last, _) = run(&mut device, 2, Request::Capture { seconds: 5 });
    assert!(matches!(last, Response::Captured { .. }), "{last:?}");
}

#[test]
fn the_chip_s_fit_keeps_the_filter_its_captures_were_taken_through() {
    use shared::protocol::{LowPassFilter, SensorConfig};
    let mut device = boot(SimMpu6050::settled(12), Flash::new());
    let config = SensorConfig { filter: LowPassFilter::Hz21, ..SensorConfig::default() };
    let configured = ask(&mut device, 1, Request::Configure(config));
    assert!(matches!(configured, Response::Configured(c) if c.filter == LowPassFilter::Hz21), "{configured:?}");
    for position in Position::ALL {
        capture_at(&mut device, position.specific_force_g());
    }
    let Response::Fitted(calibration) = ask(&mut device, 8, Request::FitSixPosition) else { panic!("no fit") };
    assert_eq!(calibration.filter, LowPassFilter::Hz21);
}
