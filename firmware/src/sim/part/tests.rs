//! The simulated parts under the real driver: each named, its family configured as it needs, its
//! temperature read right.

use embassy_futures::block_on;
use embedded_hal::i2c::I2c;
use shared::part::{Family, Part};
use shared::protocol::{LowPassFilter, SensorConfig};

use super::{SimPart, SIM_PART_NAMES};
use crate::sensor::{RawSample, Sensor};
use crate::sim::physics::ACCEL_NOISE_DENSITY_G;
use crate::sim::thermal::Environment;
use crate::sim::SimMpu6050;

fn sim_of(part: SimPart, seed: u64) -> SimMpu6050 {
    SimMpu6050::settled(seed).with_part(part)
}

#[test]
fn each_simulated_part_is_identified_by_name_and_family() {
    let expected = [
        (Part::Mpu6050, "MPU-6050", Family::Mpu6050),
        (Part::Mpu6500, "MPU-6500", Family::Mpu6500),
        (Part::Mpu9250, "MPU-9250", Family::Mpu6500),
        (Part::Icm20689, "ICM-20689", Family::Mpu6500),
        (Part::Unknown(0x72), "unknown", Family::Mpu6500),
    ];
    for (name, (part, part_name, family)) in SIM_PART_NAMES.iter().zip(expected) {
        let mut sim = sim_of(SimPart::by_name(name).unwrap(), 1);
        let id = block_on(Sensor::probe(&mut sim)).unwrap().identity().identification();
        assert_eq!((id.part, id.part.name(), id.family), (part, part_name, family), "--sim-part {name}");
        assert!(!id.contradicts_who_am_i(), "{name}");
    }
}

#[test]
fn a_6500_family_map_that_answers_0x68_is_flagged() {
    let mut sim = sim_of(SimPart { who_am_i: 0x68, ..SimPart::mpu6500() }, 2);
    let id = block_on(Sensor::probe(&mut sim)).unwrap().identity().identification();
    assert_eq!((id.part, id.family), (Part::Mpu6050, Family::Mpu6500));
    assert!(id.contradicts_who_am_i());
}

#[test]
fn probing_the_family_leaves_the_registers_it_tried_as_they_were() {
    let mut sim = sim_of(SimPart::mpu6500(), 3);
    sim.write(0x68, &[0x77, 0x3C]).unwrap(); // XA_OFFSET_H: a factory offset
    block_on(Sensor::probe(&mut sim)).unwrap();
    let mut value = [0u8];
    sim.write_read(0x68, &[0x77], &mut value).unwrap();
    assert_eq!(value, [0x3C]);
}

/// The accelerometer noise bandwidth the samples show, in Hz: (std / density)^2, over 3 axes.
fn noise_bandwidth_hz(sim: &mut SimMpu6050, sensor: &mut Sensor, seconds: u32) -> f32 {
    block_on(sensor.start_fifo(sim)).unwrap();
    let (mut n, mut sum, mut sum_sq) = (0f64, [0f64; 3], [0f64; 3]);
    let mut buffer = [RawSample::default(); 64];
    for _ in 0..seconds * 20 {
        sim.advance_us(50_000);
        let count = block_on(sensor.read_fifo(sim, &mut buffer)).unwrap();
        for sample in &buffer[..count] {
            n += 1.0;
            for axis in 0..3 {
                let g = f64::from(sample.accel[axis]) / 16384.0;
                sum[axis] += g;
                sum_sq[axis] += g * g;
            }
        }
    }
    let variance: f64 = (0..3).map(|a| sum_sq[a] / n - (sum[a] / n).powi(2)).sum::<f64>() / 3.0;
    (variance / f64::from(ACCEL_NOISE_DENSITY_G).powi(2)) as f32
}

#[test]
fn on_the_6500_family_the_configured_low_pass_sets_the_accelerometer_noise() {
    let config = SensorConfig { filter: LowPassFilter::Hz44, ..SensorConfig::default() };
    let parts = [SimPart::mpu6500(), SimPart::mpu9250(), SimPart::icm20689(), SimPart::unknown72()];
    for (seed, part) in parts.into_iter().enumerate() {
        let mut sim = sim_of(part, 40 + seed as u64);
        let mut sensor = block_on(Sensor::probe(&mut sim)).unwrap();
        block_on(sensor.configure(&mut sim, config)).unwrap();
        // NOTE: RM-MPU-6500A 4.8: A_DLPF_CFG 3 is 41 Hz, the nearest to the MPU-6050's 44 Hz.
        let filtered = noise_bandwidth_hz(&mut sim, &mut sensor, 60);
        assert!((filtered / 41.0 - 1.0).abs() < 0.10, "{part:?}: {filtered} Hz, want 41 Hz");
        // What a driver that writes CONFIG only leaves: ACCEL_CONFIG2 at reset, 460 Hz.
        sim.write(0x68, &[0x1D, 0x00]).unwrap();
        let unfiltered = noise_bandwidth_hz(&mut sim, &mut sensor, 60);
        assert!((unfiltered / 460.0 - 1.0).abs() < 0.10, "{part:?}: {unfiltered} Hz, want 460 Hz");
    }
}

#[test]
fn the_temperature_read_is_the_simulated_die_temperature_on_every_family() {
    for (i, name) in SIM_PART_NAMES.iter().enumerate() {
        for die_c in [-5.0, 21.0, 31.7, 60.0] {
            let mut sim = sim_of(SimPart::by_name(name).unwrap(), 5 + i as u64);
            sim.physics.environment = Environment::fixed(die_c);
            let mut sensor = block_on(Sensor::probe(&mut sim)).unwrap();
            block_on(sensor.configure(&mut sim, SensorConfig::default())).unwrap();
            sim.advance_us(20_000);
            let read_c = block_on(sensor.read_latest(&mut sim)).unwrap().temp_c();
            assert!((read_c - die_c).abs() < 1.0, "{name} at {die_c} degC read {read_c} degC");
        }
    }
}

/// The mean accelerometer output over 2 s at 100 Hz, in g (+-2 g, 16384 LSB/g).
fn mean_accel_g(sim: &mut SimMpu6050, sensor: &mut Sensor) -> [f64; 3] {
    let mut sum = [0.0; 3];
    for _ in 0..200 {
        sim.advance_us(10_000);
        let sample = block_on(sensor.read_latest(sim)).unwrap();
        for (total, lsb) in sum.iter_mut().zip(sample.accel) {
            *total += f64::from(lsb) / 16384.0 / 200.0;
        }
    }
    sum
}

/// Writes a big-endian offset pair at `high` (the high byte's address).
fn write_pair(sim: &mut SimMpu6050, high: u8, word: i16) {
    let [h, l] = word.to_be_bytes();
    sim.write(0x68, &[high, h, l]).unwrap();
}

fn read_pair(sim: &mut SimMpu6050, high: u8) -> i16 {
    let mut bytes = [0u8; 2];
    sim.write_read(0x68, &[high], &mut bytes).unwrap();
    i16::from_be_bytes(bytes)
}

#[test]
fn each_family_applies_its_own_accelerometer_offset_registers_in_0_98_mg_steps_and_ignores_the_others() {
    // NOTE: the MPU-6050's XA/YA/ZA_OFFS_H at 0x06, 0x08, 0x0A (offset-register application note); the
    // MPU-6500 family's XA/YA/ZA_OFFSET_H at 0x77, 0x7A, 0x7D (RM-MPU-6500A registers 119-126). A
    // pair is a 15-bit value in bits 15:1, 1/1024 g a step; bit 0 is reserved.
    let cases = [(SimPart::mpu6050(), [0x06, 0x08, 0x0A], 0x77), (SimPart::icm20689(), [0x77, 0x7A, 0x7D], 0x06)];
    for (seed, (part, own, other)) in cases.into_iter().enumerate() {
        let mut sim = sim_of(part, 60 + seed as u64);
        let mut sensor = block_on(Sensor::probe(&mut sim)).unwrap();
        block_on(sensor.configure(&mut sim, SensorConfig::default())).unwrap();
        let factory = own.map(|high| read_pair(&mut sim, high));
        assert_eq!(factory, part.factory_offsets, "{part:?}: the factory's offsets at power-up");
        let before = mean_accel_g(&mut sim, &mut sensor);
        // The factory's values are part of the output already: +Z up reads (0, 0, 1) g within the
        // published model's offsets and sensitivity errors (tens of mg).
        let gravity_error_g = [before[0], before[1], before[2] - 1.0].map(f64::abs).into_iter().fold(0.0, f64::max);
        assert!(gravity_error_g < 0.1, "{part:?}: {before:?}");
        // x: +256 (128 steps, +125 mg); y: -512 (-250 mg); z: bit 0 only (nothing).
        for (high, (word, change)) in own.into_iter().zip(factory.into_iter().zip([256, -512, 0])) {
            write_pair(&mut sim, high, if change == 0 { word ^ 1 } else { word + change });
        }
        write_pair(&mut sim, other, 0x4000); // the other family's x offset: 8 g, were it applied
        let after = mean_accel_g(&mut sim, &mut sensor);
        for (axis, wanted_g) in [0.125, -0.25, 0.0].into_iter().enumerate() {
            let moved_g = after[axis] - before[axis];
            // NOTE: two means of 200 samples of 2.8 mg noise differ by 0.3 mg rms.
            assert!((moved_g - wanted_g).abs() < 0.0015, "{part:?} axis {axis}: moved {moved_g} g, want {wanted_g} g");
        }
        sim.write(0x68, &[0x6B, 0x80]).unwrap(); // PWR_MGMT_1: DEVICE_RESET
        assert_eq!(own.map(|high| read_pair(&mut sim, high)), factory, "{part:?}: a reset reloads the factory's");
    }
}

#[test]
fn a_part_that_ignores_its_offset_registers_keeps_what_is_written_and_its_output_does_not_move() {
    let mut sim = sim_of(SimPart::mpu6500().ignoring_offsets(), 70);
    let mut sensor = block_on(Sensor::probe(&mut sim)).unwrap();
    block_on(sensor.configure(&mut sim, SensorConfig::default())).unwrap();
    let before = mean_accel_g(&mut sim, &mut sensor);
    write_pair(&mut sim, 0x77, 0x4000);
    assert_eq!(read_pair(&mut sim, 0x77), 0x4000);
    let moved_g = mean_accel_g(&mut sim, &mut sensor)[0] - before[0];
    assert!(moved_g.abs() < 0.0015, "moved {moved_g} g");
}
