//! Driver-level tests against embedded-hal-mock transaction lists. Register addresses are written out
//! from the datasheet (Register Map rev 4.2) rather than taken from the code under test.

use embassy_futures::block_on;
use embedded_hal::i2c::{ErrorKind, NoAcknowledgeSource};
use embedded_hal_mock::eh1::i2c::{Mock, Transaction as T};
use shared::part::Family;
use shared::protocol::{LowPassFilter, SensorConfig};
use shared::AccelRange;

use super::{Error, RawSample, Sensor};

const NACK: ErrorKind = ErrorKind::NoAcknowledge(NoAcknowledgeSource::Address);

fn who_am_i(address: u8, value: u8) -> T {
    T::write_read(address, vec![0x75], vec![value])
}

/// The family check: ACCEL_CONFIG2 (0x1D) then XA_OFFSET_H (0x77) read, written with bits 0 and 2
/// flipped, read back (as `kept` says) and restored.
fn family_check(address: u8, kept: bool) -> Vec<T> {
    let mut transactions = Vec::new();
    for register in [0x1D, 0x77] {
        let read_back = if kept { 0x05 } else { 0x00 };
        transactions.extend([
            T::write_read(address, vec![register], vec![0x00]),
            T::write(address, vec![register, 0x05]),
            T::write_read(address, vec![register], vec![read_back]),
            T::write(address, vec![register, 0x00]),
        ]);
    }
    transactions
}

fn probed(address: u8) -> Sensor {
    let mut answers = vec![who_am_i(0x68, 0).with_error(NACK), who_am_i(0x69, 0x68)];
    if address == 0x68 {
        answers = vec![who_am_i(0x68, 0x68)];
    }
    answers.extend(family_check(address, false));
    let mut bus = Mock::new(&answers);
    let sensor = block_on(Sensor::probe(&mut bus)).unwrap();
    bus.done();
    sensor
}

#[test]
fn probe_finds_a_genuine_mpu6050_at_0x68_and_restores_the_registers_it_tried() {
    let mut bus = Mock::new(&[vec![who_am_i(0x68, 0x68)], family_check(0x68, false)].concat());
    let identity = block_on(Sensor::probe(&mut bus)).unwrap().identity();
    assert_eq!((identity.address, identity.who_am_i, identity.family), (0x68, 0x68, Family::Mpu6050));
    bus.done();
}

#[test]
fn probe_falls_back_to_0x69_when_0x68_does_not_acknowledge() {
    let answers = [vec![who_am_i(0x68, 0).with_error(NACK), who_am_i(0x69, 0x68)], family_check(0x69, false)];
    let mut bus = Mock::new(&answers.concat());
    assert_eq!(block_on(Sensor::probe(&mut bus)).unwrap().identity().address, 0x69);
    bus.done();
}

#[test]
fn probe_runs_a_look_alike_as_the_family_its_registers_show() {
    let mut bus = Mock::new(&[vec![who_am_i(0x68, 0x72)], family_check(0x68, true)].concat());
    let identity = block_on(Sensor::probe(&mut bus)).unwrap().identity();
    assert_eq!((identity.who_am_i, identity.family), (0x72, Family::Mpu6500));
    bus.done();
}

#[test]
fn probe_reports_a_missing_sensor_when_nothing_answers() {
    let mut bus = Mock::new(&[who_am_i(0x68, 0).with_error(NACK), who_am_i(0x69, 0).with_error(NACK)]);
    assert_eq!(block_on(Sensor::probe(&mut bus)), Err(Error::Missing));
    bus.done();
}

#[test]
fn probe_names_an_unknown_chip_and_its_id() {
    let mut bus = Mock::new(&[who_am_i(0x68, 0x19)]);
    assert_eq!(block_on(Sensor::probe(&mut bus)), Err(Error::UnknownChip { address: 0x68, who_am_i: 0x19 }));
    bus.done();
}

#[test]
fn configure_wakes_the_chip_and_sets_range_filter_and_rate() {
    let mut sensor = probed(0x69);
    let mut bus = Mock::new(&[
        T::write(0x69, vec![0x6B, 0x01]), // PWR_MGMT_1: awake, PLL on x gyro
        T::write(0x69, vec![0x1C, 0x10]), // ACCEL_CONFIG: AFS_SEL = 2 (+-8 g), self-test off
        T::write(0x69, vec![0x1B, 0x10]), // GYRO_CONFIG: FS_SEL = 2 (+-1000 deg/s), self-test off
        T::write(0x69, vec![0x1A, 0x04]), // CONFIG: DLPF_CFG = 4 (21 Hz)
        T::write(0x69, vec![0x19, 0x04]), // SMPLRT_DIV: 1 kHz / (1 + 4) = 200 Hz
        T::write(0x69, vec![0x38, 0x10]), // INT_ENABLE: FIFO_OFLOW_EN
    ]);
    let wanted = SensorConfig { range: AccelRange::G8, sample_rate_hz: 200, filter: LowPassFilter::Hz21 };
    assert_eq!(block_on(sensor.configure(&mut bus, wanted)), Ok(wanted));
    bus.done();
}

#[test]
fn configure_refuses_a_rate_the_1khz_clock_cannot_divide_to_without_touching_the_bus() {
    let mut sensor = probed(0x68);
    let mut bus = Mock::new(&[]);
    for rate_hz in [0, 3, 300, 1001] {
        let config = SensorConfig { sample_rate_hz: rate_hz, ..SensorConfig::default() };
        assert_eq!(block_on(sensor.configure(&mut bus, config)), Err(Error::InvalidRate { rate_hz }));
    }
    bus.done();
}

#[test]
fn start_fifo_resets_it_clears_the_overflow_flag_and_enables_temp_gyro_and_accel() {
    let mut sensor = probed(0x68);
    let mut bus = Mock::new(&[
        T::write(0x68, vec![0x23, 0x00]),            // FIFO_EN: nothing
        T::write(0x68, vec![0x6A, 0x04]),            // USER_CTRL: FIFO_RESET
        T::write_read(0x68, vec![0x3A], vec![0x10]), // INT_STATUS read clears it
        T::write(0x68, vec![0x23, 0xF8]),            // FIFO_EN: TEMP, XG, YG, ZG, ACCEL
        T::write(0x68, vec![0x6A, 0x40]),            // USER_CTRL: FIFO_EN
    ]);
    block_on(sensor.start_fifo(&mut bus)).unwrap();
    bus.done();
}

#[test]
fn read_fifo_pops_only_whole_samples_in_register_order() {
    let mut sensor = probed(0x68);
    let first = [0x40, 0x00, 0xC0, 0x00, 0x00, 0x01, 0xF2, 0x30, 0x00, 0x83, 0xFF, 0x7D, 0x00, 0x00];
    let second = [0x7F, 0xFF, 0x80, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x05];
    let both: Vec<u8> = first.iter().chain(&second).copied().collect();
    let mut bus = Mock::new(&[
        T::write_read(0x68, vec![0x3A], vec![0x01]), // INT_STATUS: data ready, no overflow
        T::write_read(0x68, vec![0x72], vec![0x00, 30]), // FIFO_COUNT: 30 bytes = 2 samples + 2
        T::write_read(0x68, vec![0x74], both),       // FIFO_R_W: 28 bytes
    ]);
    let mut out = [RawSample::default(); 4];
    assert_eq!(block_on(sensor.read_fifo(&mut bus, &mut out)), Ok(2));
    assert_eq!(out[0], RawSample { accel: [16384, -16384, 1], temp: -3536, gyro: [131, -131, 0] });
    assert_eq!(out[1], RawSample { accel: [32767, -32768, 0], temp: 0, gyro: [0, 0, 5] });
    assert!((out[0].temp_c() - 26.13).abs() < 0.01, "{}", out[0].temp_c());
    bus.done();
}

#[test]
fn read_fifo_reports_an_overflow_before_reading_misaligned_bytes() {
    let mut sensor = probed(0x68);
    let mut bus = Mock::new(&[T::write_read(0x68, vec![0x3A], vec![0x11])]);
    let mut out = [RawSample::default(); 4];
    assert_eq!(block_on(sensor.read_fifo(&mut bus, &mut out)), Err(Error::FifoOverflow));
    bus.done();
}

#[test]
fn a_failing_transaction_is_a_bus_error() {
    let mut sensor = probed(0x68);
    let mut bus = Mock::new(&[T::write_read(0x68, vec![0x3B], vec![0; 14]).with_error(NACK)]);
    assert_eq!(block_on(sensor.read_latest(&mut bus)), Err(Error::I2c(NACK)));
    bus.done();
}
