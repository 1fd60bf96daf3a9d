//! The simulated MPU-6050 under the real driver and capture engine.

use embassy_futures::block_on;
use shared::linalg::{self, Vec3};
use shared::protocol::{CaptureStats, DeviceError, SensorConfig};

use super::physics::{Motion, Physics, ACCEL_NOISE_DENSITY_G};
use super::SimMpu6050;
use crate::capture::Capture;
use crate::sensor::{Error, RawSample, Sensor};

/// How often the board loop drains the FIFO, in microseconds.
const POLL_US: u64 = 50_000;

fn configured(sim: &mut SimMpu6050, config: SensorConfig) -> Sensor {
    let mut sensor = block_on(Sensor::probe(sim)).expect("simulated sensor answers");
    block_on(sensor.configure(sim, config)).expect("configures");
    sensor
}

/// Runs one capture as the device does: drain the FIFO every 50 ms until rate x seconds samples.
fn capture(sim: &mut SimMpu6050, config: SensorConfig, seconds: u8) -> Result<CaptureStats, DeviceError> {
    let mut sensor = configured(sim, config);
    let mut capture = Capture::new(seconds, sensor.config())?;
    block_on(sensor.start_fifo(sim)).unwrap();
    let mut buffer = [RawSample::default(); 32];
    while !capture.is_complete() {
        sim.advance_us(POLL_US);
        loop {
            let n = block_on(sensor.read_fifo(sim, &mut buffer)).map_err(|e| e.to_device_error())?;
            capture.take(&buffer[..n]);
            if n < buffer.len() {
                break;
            }
        }
    }
    capture.finish()
}

#[test]
fn who_am_i_and_address_follow_the_configuration() {
    let mut sim = SimMpu6050::new(1).with_address(0x69).with_who_am_i(0x72);
    let identity = block_on(Sensor::probe(&mut sim)).unwrap().identity();
    assert_eq!((identity.address, identity.who_am_i), (0x69, 0x72));
    sim.set_connected(false);
    assert_eq!(block_on(Sensor::probe(&mut sim)), Err(Error::Missing));
}

#[test]
fn sample_count_equals_rate_times_seconds_exactly() {
    for (rate_hz, seconds) in [(100, 10), (200, 5), (50, 20), (1000, 5)] {
        let mut sim = SimMpu6050::new(u64::from(rate_hz));
        let config = SensorConfig { sample_rate_hz: rate_hz, ..SensorConfig::default() };
        let stats = capture(&mut sim, config, seconds).unwrap();
        assert_eq!(stats.samples, u32::from(rate_hz) * u32::from(seconds));
        assert_eq!(stats.seconds, f32::from(seconds));
    }
}

#[test]
fn the_mean_lies_within_4_sigma_of_the_true_reading() {
    // NOTE: white noise of density n averaged over T seconds has sigma n / sqrt(2 T): 89 ug at 10 s.
    let sigma = ACCEL_NOISE_DENSITY_G / (2.0f32 * 10.0).sqrt();
    let ups: [Vec3<f32>; 5] = [[0.0, 0.0, 1.0], [-1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.3, -0.5, 0.8], [0.0, 0.0, -1.0]];
    for (seed, up) in ups.into_iter().enumerate() {
        // NOTE: the settled static sensor: white noise is the only error this test allows.
        let mut sim = SimMpu6050::settled(seed as u64 + 10);
        sim.place(up);
        let truth = sim.physics.truth.reading_g(linalg::scale(up, 1.0 / linalg::norm(up)));
        let stats = capture(&mut sim, SensorConfig::default(), 10).unwrap();
        for (axis, (mean, true_mean)) in stats.mean_g.iter().zip(truth).enumerate() {
            let error = (mean - true_mean).abs();
            assert!(error < 4.0 * sigma, "up {up:?} axis {axis}: error {error:e} g, 4 sigma {:e}", 4.0 * sigma);
        }
        // The capture measures the per-sample noise too: 400 ug * sqrt(50 Hz) = 2.83 mg.
        assert!((stats.std_g[0] - 2.83e-3).abs() < 0.2e-3, "std {}", stats.std_g[0]);
        assert!((stats.gyro_mean_dps[0] - sim.physics.truth.gyro_bias_dps[0]).abs() < 0.01);
    }
}

#[test]
fn still_captures_are_almost_never_called_moved() {
    let mut sim = SimMpu6050::new(99);
    let mut false_alarms = 0;
    for _ in 0..200 {
        if let Err(DeviceError::Moved { .. }) = capture(&mut sim, SensorConfig::default(), 10) {
            false_alarms += 1;
        }
    }
    assert!(false_alarms <= 2, "{false_alarms} of 200 still captures were called moved");
}

#[test]
fn a_board_turned_or_shaken_during_the_capture_is_called_moved() {
    let motions = [
        Motion::Rotating { axis: [1.0, 0.0, 0.0], rate_dps: 1.0 }, // 10 degrees over the capture
        Motion::Vibrating { amplitude_g: 0.05, frequency_hz: 8.0 }, // a hand's tremor
    ];
    for motion in motions {
        let mut sim = SimMpu6050::new(5);
        sim.set_motion(motion);
        let result = capture(&mut sim, SensorConfig::default(), 10);
        assert!(matches!(result, Err(DeviceError::Moved { .. })), "{motion:?}: {result:?}");
    }
}

#[test]
fn saturation_refuses_the_capture_as_clipped() {
    let mut sim = SimMpu6050::new(6);
    sim.place([1.0, 0.0, 0.0]);
    sim.set_motion(Motion::Vibrating { amplitude_g: 1.5, frequency_hz: 2.0 }); // x reaches 2.5 g at +-2 g
    let result = capture(&mut sim, SensorConfig::default(), 5);
    assert!(matches!(result, Err(DeviceError::Clipped { samples }) if samples > 50), "{result:?}");
}

#[test]
fn a_stalled_reader_sees_a_fifo_overflow() {
    let mut sim = SimMpu6050::new(7);
    let mut sensor = configured(&mut sim, SensorConfig::default());
    block_on(sensor.start_fifo(&mut sim)).unwrap();
    sim.advance_us(700_000); // 70 samples of 14 bytes: 980 of 1024 bytes
    let mut buffer = [RawSample::default(); 128];
    assert_eq!(block_on(sensor.read_fifo(&mut sim, &mut buffer)), Ok(70));
    sim.advance_us(800_000); // 80 samples: 1120 bytes, more than the FIFO holds
    assert_eq!(block_on(sensor.read_fifo(&mut sim, &mut buffer)), Err(Error::FifoOverflow));
    // Restarting the FIFO clears the condition.
    block_on(sensor.start_fifo(&mut sim)).unwrap();
    sim.advance_us(100_000);
    assert_eq!(block_on(sensor.read_fifo(&mut sim, &mut buffer)), Ok(10));
}

#[test]
fn an_asleep_chip_fills_no_fifo_until_it_is_woken() {
    use embedded_hal::i2c::I2c;
    // Register addresses from the register map rev 4.2: CONFIG 0x1A, SMPLRT_DIV 0x19, FIFO_EN 0x23,
    // USER_CTRL 0x6A, PWR_MGMT_1 0x6B.
    let mut sim = SimMpu6050::new(8);
    let setup: [&[u8]; 4] = [&[0x1A, 0x03], &[0x19, 9], &[0x23, 0xF8], &[0x6A, 0x40]]; // 100 Hz, FIFO on
    for bytes in setup {
        sim.write(0x68, bytes).unwrap();
    }
    sim.advance_us(1_000_000);
    assert_eq!(sim.fifo_len(), 0, "asleep since power-up, yet the FIFO filled");
    sim.write(0x68, &[0x6B, 0x01]).unwrap(); // awake, PLL on x gyro
    sim.advance_us(500_000);
    assert_eq!(sim.fifo_len(), 50 * 14, "awake, 0.5 s at 100 Hz of 14-byte samples");
}

#[test]
fn simulated_boards_have_distinct_serial_numbers_marked_as_simulated() {
    let (first, second) = (super::sim_serial_number(1), super::sim_serial_number(2));
    assert_ne!(first, second);
    assert_eq!(&first.hex(), b"53494D000000000000000001", "\"SIM\", a zero, then the seed");
}

#[test]
fn a_turn_that_stops_leaves_the_board_at_its_new_orientation() {
    let mut sim = SimMpu6050::new(5);
    sim.set_motion(Motion::Rotating { axis: [1.0, 0.0, 0.0], rate_dps: 90.0 });
    sim.advance_us(1_000_000);
    sim.stop_motion();
    // A quarter turn about +x from +Z up brings +Y up; the board then rests.
    let up = sim.physics.up;
    assert!(linalg::norm(linalg::sub(up, [0.0, 1.0, 0.0])) < 1e-3, "up {up:?}");
    assert_eq!(sim.physics.motion, Motion::Still);
}

#[test]
fn parts_drawn_by_seed_spread_as_the_datasheet_tolerances_say_and_the_first_power_on_changes_nothing() {
    let parts: Vec<Physics> = (1..=2000)
        .map(|seed| {
            let mut physics = Physics::new(seed);
            physics.drawn_part(seed);
            physics
        })
        .collect();
    let spread = |value: &dyn Fn(&Physics) -> f32| {
        let values: Vec<f64> = parts.iter().map(|p| f64::from(value(p))).collect();
        let mean = values.iter().sum::<f64>() / values.len() as f64;
        (values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (values.len() - 1) as f64).sqrt()
    };
    // NOTE: 2000 draws know a standard deviation to 1.6 %; 5 % is three of those.
    let within = |found: f64, wanted: f64, what: &str| assert!((found / wanted - 1.0).abs() < 0.05, "{what}: {found}");
    within(spread(&|p| p.truth.offset_g[2]), 40e-3, "z offset, g");
    within(spread(&|p| p.truth.matrix[1][1]), 0.015 * 1.003, "y sensitivity");
    within(spread(&|p| p.truth.matrix[0][2] / p.truth.matrix[2][2]), 0.01, "non-orthogonality a_zy");
    within(spread(&|p| p.drift.offset_g[0][0]), 1e-3, "x offset drift, g/degC");
    within(spread(&|p| p.drift.scale[0][1]), 2e-4, "y sensitivity drift, 1/degC");
    let mut first = Physics::new(7);
    first.power_on(0, 0.0);
    assert_eq!(first.truth, Physics::new(7).truth);
}

/// The register accesses of a bytewise bus: `(register, bytes)` writes, then reads of `count` bytes.
fn bytewise_reads(chip: &mut SimMpu6050, writes: &[(u8, &[u8])], reads: &[(u8, usize)]) -> Vec<u8> {
    let mut bus = super::BytewiseTarget::default();
    for (register, values) in writes {
        assert!(bus.address(chip, 0x68));
        bus.write(chip, *register);
        values.iter().for_each(|&v| bus.write(chip, v));
    }
    let mut read = Vec::new();
    for &(register, count) in reads {
        assert!(bus.address(chip, 0x68));
        bus.write(chip, register);
        assert!(bus.address(chip, 0x68)); // the repeated start, to read
        read.extend((0..count).map(|_| bus.read(chip)));
    }
    read
}

#[test]
fn a_bus_that_arrives_byte_by_byte_reads_and_writes_as_whole_transactions_do() {
    use embedded_hal::i2c::I2c;
    // PWR_MGMT_1 (0x6B) awake, USER_CTRL (0x6A) FIFO on, FIFO_EN (0x23) accelerometer and gyro.
    let writes: [(u8, &[u8]); 2] = [(0x6B, &[0x00]), (0x6A, &[0x40])];
    let fifo_en: (u8, &[u8]) = (0x23, &[0x78]);
    let (mut bytewise, mut whole) = (SimMpu6050::new(5), SimMpu6050::new(5));
    for (register, values) in writes.iter().chain([&fifo_en]) {
        whole.write(0x68, &[&[*register][..], values].concat()).unwrap();
    }
    bytewise_reads(&mut bytewise, &[writes[0], writes[1], fifo_en], &[]);
    bytewise.advance_us(30_000);
    whole.advance_us(30_000);
    // WHO_AM_I (0x75), the data registers from ACCEL_XOUT_H (0x3B), 24 bytes of FIFO_R_W (0x74).
    let read = bytewise_reads(&mut bytewise, &[], &[(0x75, 1), (0x3B, 14), (0x74, 24)]);
    let mut expected = vec![0u8; 39];
    whole.write_read(0x68, &[0x75], &mut expected[..1]).unwrap();
    whole.write_read(0x68, &[0x3B], &mut expected[1..15]).unwrap();
    whole.write_read(0x68, &[0x74], &mut expected[15..]).unwrap();
    assert_eq!(read[0], 0x68);
    assert_eq!(read, expected);
    assert_ne!(read[15..27], read[27..], "two FIFO samples read as one: FIFO_R_W must pop, not advance");
    assert!(!super::BytewiseTarget::default().address(&mut bytewise, 0x69), "0x69 acknowledged");
}
