//! The computations run both on an emulated Cortex-M4F (src/main.rs, under QEMU) and on the host
//! (tests/on_target.rs), so their results can be compared bit for bit.
#![cfg_attr(not(test), no_std)]

use embassy_futures::block_on;
use firmware::device::sample_message;
use firmware::device::Device;
use firmware::sensor::RawSample;
use firmware::sim::{sim_serial_number, SimFlash, SimMpu6050, SIM_FLASH_RANGE};
use shared::calibration::{GyroCalibration, TemperatureModel};
use shared::protocol::{Request, Response, SensorConfig, StreamKind};
use shared::real::Real;
use shared::{AccelRange, Calibration, Position, PositionMap};

/// The published phone readings in m/s^2 (Georgieva and Hofreither), the six faces in their order.
const PHONE: [(Position, [f32; 3]); 6] = [
    (Position::NegX, [-9.54983, 0.37829, -0.999283]),
    (Position::PosX, [10.145, 0.314528, -1.37789]),
    (Position::NegY, [0.413309, -9.47641, -1.62076]),
    (Position::PosY, [0.368766, 10.1442, -0.910232]),
    (Position::NegZ, [0.510292, 0.338026, -10.7851]),
    (Position::PosZ, [0.231834, 0.482186, 8.60553]),
];

// NOTE: the emulated chip's start-up and semihosting: a Cortex-M4F's, or a generic RV32IMC's (only
// `fit-count` is built for it); both crates name their parts alike.
#[cfg(all(target_os = "none", target_arch = "arm"))]
pub use {
    cortex_m::asm::{nop, wfi},
    cortex_m_rt::entry,
    cortex_m_semihosting as semihosting,
};
#[cfg(all(target_os = "none", target_arch = "riscv32"))]
pub use {
    riscv::asm::{nop, wfi},
    riscv_rt::entry,
    riscv_semihosting as semihosting,
};

/// Ends an emulated run: says `done` (or `failed`) over semihosting and exits QEMU with that status.
#[cfg(target_os = "none")]
pub fn finish(ok: bool) -> ! {
    use semihosting::{debug, hprintln};
    hprintln!("{}", if ok { "done" } else { "failed" });
    debug::exit(if ok { debug::EXIT_SUCCESS } else { debug::EXIT_FAILURE });
    // NOTE: semihosting exit ends QEMU; should it not, sleep rather than spin.
    loop {
        wfi();
    }
}

/// Says what panicked over semihosting and exits QEMU with a failure.
#[cfg(target_os = "none")]
#[panic_handler]
fn panic(info: &core::panic::PanicInfo) -> ! {
    semihosting::hprintln!("panic: {}", info);
    semihosting::debug::exit(semihosting::debug::EXIT_FAILURE);
    loop {
        wfi();
    }
}

/// One named result: f32 values as their bit patterns.
pub struct Result<'a> {
    /// What was computed.
    pub name: &'a str,
    /// The values.
    pub values: &'a [f32],
}

/// Runs every computation and hands each result to `report`; `false` when one could not run.
pub fn run(report: &mut impl FnMut(Result<'_>)) -> bool {
    phone_six_position(report)
        && device_calibration(report)
        && thermal_correction(report)
        && ortho9_session(report)
        && device_ortho9(report)
        && gyro_turn_correction(report)
}

/// The quick calibration's ten orientations (six faces, four tetrahedron corners), each tilted about
/// 4 degrees in its own direction, as a hand leaves them; not unit length (the board normalises).
pub const QUICK_TILTED: [[f32; 3]; 10] = [
    [0.62, 0.62, 0.54],
    [-0.54, -0.62, 0.62],
    [-1.0, 0.0, -0.07],
    [1.0, 0.0, 0.07],
    [0.0, -0.07, -1.0],
    [0.0, 0.07, 1.0],
    [0.07, 1.0, 0.0],
    [-0.07, -1.0, 0.0],
    [-0.54, 0.62, -0.62],
    [0.54, -0.62, -0.62],
];

/// The quick calibration's ten captures as the published-error MPU-6050 (firmware::sim's truth) reads
/// them at [`QUICK_TILTED`], in g, with a fixed pattern of +-1e-4 g standing in for noise.
pub fn quick_readings() -> [[f32; 3]; 10] {
    let truth = firmware::sim::physics::TrueErrors::published_mpu6050();
    let mut readings = [[0.0f32; 3]; 10];
    for (i, (reading, up)) in readings.iter_mut().zip(QUICK_TILTED).enumerate() {
        let length = shared::linalg::dot(up, up).root();
        *reading = truth.reading_g(up.map(|v| v / length));
        for (k, value) in reading.iter_mut().enumerate() {
            *value += 1e-4 * (((i * 3 + k) * 7 % 3) as f32 - 1.0);
        }
    }
    readings
}

/// The firmware's own 9-parameter fit on request: ten 5 s captures of the realistic simulated
/// sensor at [`QUICK_TILTED`], then `FitOrtho9`; the capture means, and the fit's M (row-major), o,
/// residual in mg, captures and iterations.
fn device_ortho9(report: &mut impl FnMut(Result<'_>)) -> bool {
    let Ok(mut device) =
        block_on(Device::boot(SimMpu6050::new(16), SimFlash::new(), SIM_FLASH_RANGE, sim_serial_number(16)))
    else {
        return false;
    };
    let mut means = [0.0f32; 30];
    for (i, up) in QUICK_TILTED.iter().enumerate() {
        device.bus_mut().place(*up);
        let Some(Response::Captured { stats, .. }) = run_to_end(&mut device, Request::Capture { seconds: 5 }, |_| {})
        else {
            return false;
        };
        means[3 * i..3 * i + 3].copy_from_slice(&stats.mean_g);
    }
    report(Result { name: "device-ortho9-means", values: &means });
    let Some(Response::Ortho9Fitted { calibration: c, captures, iterations }) =
        run_to_end(&mut device, Request::FitOrtho9, |_| {})
    else {
        return false;
    };
    let (m, o) = (c.matrix, c.offset_g);
    let values = [m[0][0], m[0][1], m[0][2], m[1][0], m[1][1], m[1][2], m[2][0], m[2][1], m[2][2], o[0], o[1], o[2]];
    report(Result { name: "device-ortho9-fit", values: &values });
    report(Result {
        name: "device-ortho9-residual-captures-iterations",
        values: &[c.residual_mg, f32::from(captures), f32::from(iterations)],
    });
    true
}

/// Samples of the turn in [`gyro_turn_raw`].
pub const GYRO_TURN_SAMPLES: usize = 100;

/// A hand's fast turn as raw counts at +-1000 deg/s (32.8 LSB per deg/s), one second at 100 Hz: a
/// parabolic rate profile about a tilted axis peaking at 24000 counts (732 deg/s) on z, on top of
/// the simulated sensor's bias. Integers only, so chip and host start from the same samples.
pub fn gyro_turn_raw() -> [RawSample; GYRO_TURN_SAMPLES] {
    let (peak, bias) = ([12_000i32, -18_000, 24_000], [-39i32, 26, 11]);
    let n = GYRO_TURN_SAMPLES as i32;
    let mut raw = [RawSample { accel: [0, 0, 16384], temp: -3920, gyro: [0; 3] }; GYRO_TURN_SAMPLES];
    for (i, sample) in raw.iter_mut().enumerate() {
        let i = i as i32;
        sample.gyro = [0, 1, 2].map(|k| (peak[k] * 4 * i * (n - i) / (n * n) + bias[k]) as i16);
    }
    raw
}

/// A calibration carrying the realistic simulated sensor's true gyro correction (its G, computed by
/// the sim's own inverse, here on the chip) and its bias at 25 degC.
pub fn gyro_calibration() -> Calibration {
    let truth = firmware::sim::physics::Physics::new(0).truth;
    let gyro = GyroCalibration { matrix: truth.gyro_matrix, bias_dps: truth.gyro_bias_dps };
    Calibration { gyro, ..Calibration::identity(AccelRange::G2) }
}

/// The firmware's one raw-sample-to-message conversion on the turn: w = G (w_raw - b) per sample.
fn gyro_turn_correction(report: &mut impl FnMut(Result<'_>)) -> bool {
    let calibration = gyro_calibration();
    let mut values = [0.0f32; 3 * GYRO_TURN_SAMPLES];
    for (i, raw) in gyro_turn_raw().iter().enumerate() {
        let sample = sample_message(raw, i as u32, 0, SensorConfig::default(), Some(&calibration));
        values[3 * i..3 * i + 3].copy_from_slice(&sample.gyro_dps);
    }
    report(Result { name: "gyro-turn-corrected", values: &values });
    report(Result { name: "gyro-matrix", values: calibration.gyro.matrix.as_flattened() });
    true
}

/// A simulated 14-position session in g: the published-error MPU-6050 (firmware::sim's truth) at the
/// six faces and the eight cube corners, with a fixed pattern of +-1e-4 g standing in for noise.
pub fn ortho9_session_readings() -> [[f32; 3]; 14] {
    let truth = firmware::sim::physics::TrueErrors::published_mpu6050();
    // NOTE: 1 / sqrt(3) as a literal: no_std f32 has no sqrt method.
    let corner = 0.577_350_26f32;
    let mut readings = [[0.0f32; 3]; 14];
    for (i, reading) in readings.iter_mut().enumerate() {
        let up = match Position::ALL.get(i) {
            Some(face) => face.specific_force_g(),
            None => [0, 1, 2].map(|k| if (i - 6) >> k & 1 == 1 { corner } else { -corner }),
        };
        *reading = truth.reading_g(up);
        for (k, value) in reading.iter_mut().enumerate() {
            *value += 1e-4 * (((i * 3 + k) * 7 % 3) as f32 - 1.0);
        }
    }
    readings
}

/// The chip's 9-parameter fit of the simulated session: its parameters and iteration count.
fn ortho9_session(report: &mut impl FnMut(Result<'_>)) -> bool {
    let Ok(fit) = shared::ortho9::fit(&ortho9_session_readings()) else { return false };
    report(Result { name: "ortho9-session-params", values: &fit.params });
    report(Result { name: "ortho9-session-iterations", values: &[fit.iterations as f32] });
    true
}

/// A calibration with a temperature model (the simulated sensor's typical drift, third order
/// included, around 25 degC), for the chip's temperature correction.
pub fn thermal_calibration() -> Calibration {
    let mut model = TemperatureModel::flat(25.0);
    model.offset_g = [[0.75e-3, -0.7e-3, 1.4e-3], [4e-6, 3e-6, -6e-6], [1e-8, -2e-8, 3e-8]];
    model.scale = [[1.2e-4, -0.8e-4, 1.6e-4], [5e-7, 0.0, -5e-7], [0.0; 3]];
    model.gyro_bias_dps = [[0.05, -0.07, 0.04], [4e-4, -3e-4, 5e-4], [0.0; 3]];
    Calibration {
        matrix: [[1.0006, 3.6e-4, -7.2e-3], [0.0, 1.003, 4.5e-4], [0.0, 0.0, 0.9834]],
        offset_g: [27.6e-3, -5.7e-3, -78.3e-3],
        gyro: GyroCalibration {
            matrix: [[0.98, 0.004, 0.0], [-0.005, 1.016, 0.006], [0.0, -0.004, 0.988]],
            bias_dps: [-1.2, 0.8, 0.35],
        },
        temperature: Some(model),
        ..Calibration::identity(AccelRange::G2)
    }
}

/// Raw samples at die temperatures of about 15, 25, 35 and 45 degC (TEMP_OUT = (T - 36.53) x 340).
pub const THERMAL_RAW: [RawSample; 4] = [
    RawSample { accel: [1200, -300, 15100], temp: -7320, gyro: [-160, 110, 40] },
    RawSample { accel: [-16050, 420, -1300], temp: -3920, gyro: [-150, 100, 50] },
    RawSample { accel: [9000, 11000, 7500], temp: -520, gyro: [-140, 90, 60] },
    RawSample { accel: [-700, -16200, -2100], temp: 2880, gyro: [-130, 80, 70] },
];

/// The firmware's one raw-sample-to-message conversion with the temperature model: every sample
/// corrected at its own die temperature.
fn thermal_correction(report: &mut impl FnMut(Result<'_>)) -> bool {
    let calibration = thermal_calibration();
    let mut values = [0.0f32; 28];
    for (i, raw) in THERMAL_RAW.iter().enumerate() {
        let sample = sample_message(raw, i as u32, 0, SensorConfig::default(), Some(&calibration));
        values[7 * i] = sample.temp_c;
        values[7 * i + 1..7 * i + 4].copy_from_slice(&sample.accel_g);
        values[7 * i + 4..7 * i + 7].copy_from_slice(&sample.gyro_dps);
    }
    report(Result { name: "thermal-corrected-samples", values: &values });
    true
}

/// shared's six-position closed form on the published phone readings, in f32.
fn phone_six_position(report: &mut impl FnMut(Result<'_>)) -> bool {
    let mut readings = PositionMap::<[f32; 3]>::new();
    for (position, reading) in PHONE {
        if readings.insert(position, reading).is_err() {
            return false;
        }
    }
    let Ok(fit) = readings.fit(9.81) else { return false };
    let m = fit.matrix;
    report(Result {
        name: "phone-six-position-matrix",
        values: &[m[0][0], m[0][1], m[0][2], m[1][0], m[1][1], m[1][2], m[2][0], m[2][1], m[2][2]],
    });
    report(Result { name: "phone-six-position-offset", values: &fit.offset });
    true
}

/// The firmware library on the simulated MPU-6050: six 5 s captures at the faces, the on-chip fit,
/// and samples corrected on the chip.
fn device_calibration(report: &mut impl FnMut(Result<'_>)) -> bool {
    let Ok(mut device) =
        block_on(Device::boot(SimMpu6050::new(2024), SimFlash::new(), SIM_FLASH_RANGE, sim_serial_number(2024)))
    else {
        return false;
    };
    let mut means = [0.0f32; 18];
    for (i, position) in Position::ALL.iter().enumerate() {
        device.bus_mut().place(position.specific_force_g());
        let Some(Response::Captured { stats, .. }) = run_to_end(&mut device, Request::Capture { seconds: 5 }, |_| {})
        else {
            return false;
        };
        means[3 * i..3 * i + 3].copy_from_slice(&stats.mean_g);
    }
    report(Result { name: "device-capture-means", values: &means });
    let Some(Response::Fitted(calibration)) = run_to_end(&mut device, Request::FitSixPosition, |_| {}) else {
        return false;
    };
    let m = calibration.matrix;
    report(Result {
        name: "device-fit-matrix",
        values: &[m[0][0], m[0][1], m[0][2], m[1][0], m[1][1], m[1][2], m[2][0], m[2][1], m[2][2]],
    });
    report(Result { name: "device-fit-offset", values: &calibration.offset_g });
    if !matches!(run_to_end(&mut device, Request::SetCalibration(calibration), |_| {}), Some(Response::Done)) {
        return false;
    }
    device.bus_mut().place([0.3, -0.4, 0.866]);
    let mut corrected = [0.0f32; 30];
    let mut count = 0;
    let stream = Request::Stream { kind: StreamKind::Calibrated, rate_hz: 50, count: 10 };
    let ended = run_to_end(&mut device, stream, |response| {
        if let (Response::Sample(sample), true) = (response, count < 10) {
            corrected[3 * count..3 * count + 3].copy_from_slice(&sample.accel_g);
            count += 1;
        }
    });
    if !matches!(ended, Some(Response::StreamEnded { samples: 10, dropped: 0 })) {
        return false;
    }
    report(Result { name: "device-corrected-samples", values: &corrected });
    true
}

/// Handles a request and polls the device (10 ms of simulated time a step) until its final response.
fn run_to_end(
    device: &mut Device<SimMpu6050, SimFlash>,
    request: Request,
    mut on_update: impl FnMut(&Response),
) -> Option<Response> {
    block_on(device.handle(1, request));
    for _ in 0..100_000 {
        while let Some((_, response)) = device.next_response() {
            match response {
                Response::Progress(_) | Response::Sample(_) => on_update(&response),
                last => return Some(last),
            }
        }
        device.bus_mut().advance_us(10_000);
        block_on(device.poll());
    }
    None
}
