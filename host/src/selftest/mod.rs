//! The datasheet self-test, run from the host through the board's register access and its raw
//! stream (the chip holds no self-test code: its flash has no room, and the procedure is the same on
//! every board).
//!
//! The procedure (RM-MPU-6000A 4.1; AN-MPU-6500A for the MPU-6500 family): the ranges the factory
//! trim assumes (the accelerometer at [`Family::self_test_range`], the gyro at +-250 deg/s), the mean
//! output with self-test off, on, and off again, each after the output has settled; the response is
//! on minus off. A board that moved during an attempt (a phase's scatter, or a baseline that shifted
//! between the two off phases) spoils it, and the attempt is repeated. The board's configuration is
//! written back at the end, whatever happened, and checked.

mod error;
pub mod history;
mod phase;
pub mod shown;
pub use accelcal_core::selftest::{report, SelfTest};

use shared::part::Family;
use shared::protocol::{DeviceInfo, LowPassFilter, SensorConfig};
use shared::selftest::{self, SelfTestRaw};

use firmware::sensor::registers::ACCEL_CONFIG;

use crate::link::{Client, LinkError, Port};
pub use error::SelfTestError;
use phase::{Phase, PhaseMeans};

use crate::limits::SELF_TEST_ATTEMPTS;
pub use phase::PhaseName;

/// The sample rate the self-test runs at, in Hz, and its filter.
///
/// NOTE: AN-MPU-6500A runs the self-test with a 92 Hz filter (the MPU-6050's nearest is 94 Hz);
/// 200 Hz divides the 1 kHz output rate and keeps the stream well within a full-speed USB port.
const SELF_TEST_RATE_HZ: u16 = 200;
const SELF_TEST_FILTER: LowPassFilter = LowPassFilter::Hz94;

/// The registers the procedure changes, from SMPLRT_DIV (0x19) to ACCEL_CONFIG2 (0x1D): saved before,
/// compared after.
const CONFIGURATION_FIRST: u8 = 0x19;
const CONFIGURATION_COUNT: u8 = 5;

/// What the procedure tells whoever runs it (and where a test moves the simulated board).
pub trait Watcher {
    /// A phase of an attempt (counted from 1) starts.
    fn phase(&mut self, attempt: u8, phase: PhaseName);
    /// The attempt was spoiled by a move and is repeated; `why` says what showed it.
    fn moved(&mut self, attempt: u8, why: &str);
}

/// Runs the self-test on the board `info` describes, and restores its configuration.
pub fn run<P: Port>(
    client: &mut Client<P>,
    info: &DeviceInfo,
    watcher: &mut dyn Watcher,
) -> Result<SelfTest, SelfTestError> {
    let identity = info.sensor.map_err(|e| SelfTestError::NoSensor(crate::link::explain(&e)))?;
    let codes = trim_codes(client, identity.family)?;
    let before = client.read_registers(CONFIGURATION_FIRST, CONFIGURATION_COUNT)?;
    let measured = measure(client, identity.family, watcher);
    // NOTE: after Ctrl-C too: the board must not be left with its self-test on.
    let interrupt = client.take_interrupt();
    let restored = restore(client, info.config, &before);
    if let Some(flag) = interrupt {
        client.interrupt_on(flag);
    }
    let (means, attempts) = measured?;
    restored?;
    let raw = SelfTestRaw { family: identity.family, codes, off_lsb: means.off_lsb, on_lsb: means.on_lsb, attempts };
    Ok(SelfTest { identity, raw, verdicts: selftest::evaluate(&raw) })
}

/// The factory-trim codes, read where the family keeps them.
fn trim_codes<P: Port>(client: &mut Client<P>, family: Family) -> Result<[u8; 6], LinkError> {
    // NOTE: RM-MPU-6000A 4.1: SELF_TEST_X/Y/Z/A at 0x0D-0x10; RM-MPU-6500A: SELF_TEST_X/Y/Z_GYRO at
    // 0x00-0x02 and _ACCEL at 0x0D-0x0F. One read of 0x00-0x10 holds both.
    let r = client.read_registers(0x00, 0x11)?;
    Ok(match family {
        Family::Mpu6050 => selftest::mpu6050_codes([r[0x0D], r[0x0E], r[0x0F], r[0x10]]),
        Family::Mpu6500 => selftest::mpu6500_codes([r[0x0D], r[0x0E], r[0x0F]], [r[0x00], r[0x01], r[0x02]]),
    })
}

/// The self-test ranges, then attempts until one is still: its means and how many it took.
fn measure<P: Port>(
    client: &mut Client<P>,
    family: Family,
    watcher: &mut dyn Watcher,
) -> Result<(PhaseMeans, u8), SelfTestError> {
    let config =
        SensorConfig { range: family.self_test_range(), sample_rate_hz: SELF_TEST_RATE_HZ, filter: SELF_TEST_FILTER };
    client.configure(config)?;
    // NOTE: the board wrote the range; the phases add the self-test bits to what it wrote.
    let accel_config = client.read_registers(ACCEL_CONFIG, 1)?[0];
    for attempt in 1..=SELF_TEST_ATTEMPTS {
        match attempt_once(client, family, accel_config, attempt, watcher)? {
            Ok(means) => return Ok((means, attempt)),
            Err(why) => watcher.moved(attempt, &why),
        }
    }
    Err(SelfTestError::KeptMoving { attempts: SELF_TEST_ATTEMPTS })
}

/// Off, on, off: the means, or why the board counts as moved.
fn attempt_once<P: Port>(
    client: &mut Client<P>,
    family: Family,
    accel_config: u8,
    attempt: u8,
    watcher: &mut dyn Watcher,
) -> Result<Result<PhaseMeans, String>, SelfTestError> {
    let mut means = [[0.0f32; 6]; 3];
    for (index, name) in PhaseName::ALL.into_iter().enumerate() {
        watcher.phase(attempt, name);
        let phase = Phase { family, name, rate_hz: SELF_TEST_RATE_HZ, accel_config };
        match phase.run(client)? {
            Ok(mean) => means[index] = mean,
            Err(why) => return Ok(Err(why)),
        }
    }
    let [before, on, after] = means;
    if selftest::baseline_moved(family, &before, &after) {
        return Ok(Err("the output with self-test off changed between before and after".to_owned()));
    }
    let off_lsb = core::array::from_fn(|axis| (before[axis] + after[axis]) / 2.0);
    Ok(Ok(PhaseMeans { off_lsb, on_lsb: on }))
}

/// Writes the board's own configuration back, empties the temperature bins the self-test's samples
/// went into, and checks the registers read as before.
fn restore<P: Port>(client: &mut Client<P>, config: SensorConfig, before: &[u8]) -> Result<(), SelfTestError> {
    client.configure(config)?;
    // NOTE: samples with self-test on are no measure of the sensor's drift with temperature.
    client.take_temperature_bins()?;
    let after = client.read_registers(CONFIGURATION_FIRST, CONFIGURATION_COUNT)?;
    if after != before {
        return Err(SelfTestError::NotRestored { before: before.to_vec(), after });
    }
    Ok(())
}

#[cfg(test)]
mod tests;
