//! The family by what its accelerometer offset registers do: a step written into each family's x
//! offset register, the output averaged before, during and after, every register restored.
//!
//! Runs through the board's generic register request and its raw stream, so the board needs no code
//! of its own (the Pico's flash has no room for any).

use shared::part::{accel_offset_g, Family};
use shared::protocol::SensorConfig;

use crate::limits::{FAMILY_BASELINE_MOVE_G, FAMILY_CHECK_ATTEMPTS, FAMILY_PHASE_MIN_SAMPLES};
use crate::link::{Client, LinkError, Port};
use crate::still::{StillError, StillPhase};

/// The two families, in the order their registers are stepped.
pub const FAMILIES: [Family; 2] = [Family::Mpu6050, Family::Mpu6500];

/// What is flipped in the x offset's high byte: bit 0, XA_OFFS[7], 128 steps of 1/1024 g (125 mg).
///
/// NOTE: only the high byte is written: the low byte holds the reserved bit 0, and on some MPU-6050
/// parts a write of a low byte lands on another axis (i2cdevlib issue 585), while every report has the
/// high bytes where the maps put them. A flip never overflows the value, unlike an addition.
const STEP_BIT: u8 = 0x01;

/// Seconds each phase lasts at the least.
const PHASE_SECONDS: f64 = 0.4;

/// The fastest stream the check asks for, in Hz (as the self-test's: well within a full-speed USB port).
const MAX_STREAM_HZ: u16 = 200;

/// What stepping one family's x offset register did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OffsetStep {
    /// The family whose register it is.
    pub family: Family,
    /// The register (the x offset's high byte).
    pub register: u8,
    /// Whether the register kept the value written (read back).
    pub kept: bool,
    /// What the step adds to the x output on a part that applies it, in g.
    pub expected_g: f64,
    /// How far the x output moved, in g (against the mean of the phases before and after).
    pub moved_g: f64,
}

/// What the measurement found.
#[derive(Debug, Clone, PartialEq)]
pub enum Measured {
    /// Both families' registers stepped on a still board, in [`FAMILIES`] order.
    Steps { steps: [OffsetStep; 2], attempts: u8 },
    /// The board moved during every attempt; `why` says what showed it the last time.
    KeptMoving { attempts: u8, why: String },
}

/// Why the offset check could not be run to its end.
#[derive(Debug, thiserror::Error)]
pub enum OffsetCheckError {
    #[error(transparent)]
    Link(#[from] LinkError),
    #[error(transparent)]
    Stream(StillError),
    #[error("the sensor's offset register 0x{register:02x} reads 0x{after:02x} after the family check, not 0x{before:02x} as before: unplug the board and plug it in again (the sensor loads its factory offsets at power-up)")]
    NotRestored { register: u8, before: u8, after: u8 },
}

impl OffsetCheckError {
    /// Whether the check could not measure but left every offset register as it found it (each
    /// step is written back and read again before a phase's samples are counted), so that what
    /// else the board reports still stands.
    pub fn left_registers_as_found(&self) -> bool {
        matches!(self, OffsetCheckError::Stream(_))
    }
}

impl From<StillError> for OffsetCheckError {
    fn from(error: StillError) -> Self {
        match error {
            StillError::Link(link) => OffsetCheckError::Link(link),
            other => OffsetCheckError::Stream(other),
        }
    }
}

/// Steps each family's x offset register in turn on a board configured as `config`, attempts until
/// the board is still; every register is written back and checked, whatever happens.
pub fn measure<P: Port>(client: &mut Client<P>, config: SensorConfig) -> Result<Measured, OffsetCheckError> {
    let phase = phase_for(config);
    let registers = FAMILIES.map(|family| family.accel_offset_registers()[0]);
    let found = [client.register(registers[0], None)?, client.register(registers[1], None)?];
    let mut why = String::new();
    for attempt in 1..=FAMILY_CHECK_ATTEMPTS {
        match attempt_once(client, &phase, registers, found)? {
            Ok(steps) => return Ok(Measured::Steps { steps, attempts: attempt }),
            Err(reason) => why = reason,
        }
    }
    Ok(Measured::KeptMoving { attempts: FAMILY_CHECK_ATTEMPTS, why })
}

/// A phase at the board's own configuration: the stream's rate, the settling after a step (the
/// filter's response) and the samples averaged.
fn phase_for(config: SensorConfig) -> StillPhase {
    let rate_hz = stream_rate_hz(config.sample_rate_hz);
    // NOTE: 1 / bandwidth is 6.3 time constants of a one-pole filter (0.2 % of a step left); the
    // MPU-6500's 5 Hz filter delays by 67 ms (RM-MPU-6500A 4.8), a third of its 200 ms.
    let settle_s = (1.0 / f64::from(config.filter.bandwidth_hz())).max(0.05);
    let per_s = f64::from(rate_hz);
    StillPhase {
        label: "family check",
        rate_hz,
        settle: (settle_s * per_s).ceil() as usize,
        samples: ((PHASE_SECONDS * per_s).ceil() as usize).max(FAMILY_PHASE_MIN_SAMPLES),
        gyro_dps_per_reported: 1.0,
    }
}

/// The fastest rate up to [`MAX_STREAM_HZ`] that divides the sample rate (a stream's rate must).
fn stream_rate_hz(sample_rate_hz: u16) -> u16 {
    (1..=sample_rate_hz.min(MAX_STREAM_HZ)).rev().find(|r| sample_rate_hz.is_multiple_of(*r)).unwrap_or(1)
}

/// The baseline, each family's step, the baseline again: the steps, or why the board counts as moved.
fn attempt_once<P: Port>(
    client: &mut Client<P>,
    phase: &StillPhase,
    registers: [u8; 2],
    found: [u8; 2],
) -> Result<Result<[OffsetStep; 2], String>, OffsetCheckError> {
    let before = match phase.mean(client)? {
        Ok(mean) => mean,
        Err(why) => return Ok(Err(why)),
    };
    let mut stepped = [(false, [0.0; 6]); 2];
    for (i, held) in stepped.iter_mut().enumerate() {
        match stepped_mean(client, phase, registers[i], found[i])? {
            (kept, Ok(mean)) => *held = (kept, mean),
            (_, Err(why)) => return Ok(Err(why)),
        }
    }
    let after = match phase.mean(client)? {
        Ok(mean) => mean,
        Err(why) => return Ok(Err(why)),
    };
    if let Some(why) = baseline_moved(&before, &after) {
        return Ok(Err(why));
    }
    let baseline_x_g = (before[0] + after[0]) / 2.0;
    Ok(Ok(core::array::from_fn(|i| OffsetStep {
        family: FAMILIES[i],
        register: registers[i],
        kept: stepped[i].0,
        expected_g: expected_step_g(found[i]),
        moved_g: stepped[i].1[0] - baseline_x_g,
    })))
}

/// Steps `register` (found holding `found`), averages a phase and writes `found` back: whether the
/// register kept the step, and the mean or why the board moved.
fn stepped_mean<P: Port>(
    client: &mut Client<P>,
    phase: &StillPhase,
    register: u8,
    found: u8,
) -> Result<(bool, Result<[f64; 6], String>), OffsetCheckError> {
    let stepped = found ^ STEP_BIT;
    let outcome = client
        .write_register(register, stepped)
        .map_err(StillError::from)
        .and_then(|held| Ok((held == stepped, phase.mean(client)?)));
    restore(client, register, found)?;
    Ok(outcome?)
}

/// Writes `found` back into `register` and checks that it reads so; after Ctrl-C too (the flag is
/// taken away for the write and given back).
fn restore<P: Port>(client: &mut Client<P>, register: u8, found: u8) -> Result<(), OffsetCheckError> {
    // NOTE: a stepped offset would shift every later reading, and every calibration made with it,
    // until the sensor loses power.
    let interrupt = client.take_interrupt();
    let restored = client.write_register(register, found);
    if let Some(flag) = interrupt {
        client.interrupt_on(flag);
    }
    let after = restored?;
    if after != found {
        return Err(OffsetCheckError::NotRestored { register, before: found, after });
    }
    Ok(())
}

/// Why the two baselines say the board moved, if they do: an accelerometer axis moved more than
/// [`FAMILY_BASELINE_MOVE_G`].
fn baseline_moved(before: &[f64; 6], after: &[f64; 6]) -> Option<String> {
    let moved_g = (0..3).map(|axis| (after[axis] - before[axis]).abs()).fold(0.0, f64::max);
    (moved_g > FAMILY_BASELINE_MOVE_G)
        .then(|| format!("the output with the offsets as found moved {:.1} mg between before and after", moved_g * 1e3))
}

/// What flipping [`STEP_BIT`] of a high byte holding `found` adds to the output, in g (+-125 mg).
pub fn expected_step_g(found: u8) -> f64 {
    f64::from(accel_offset_g(found ^ STEP_BIT, 0) - accel_offset_g(found, 0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use shared::protocol::LowPassFilter;

    #[test]
    fn a_phase_streams_at_a_rate_dividing_the_boards_and_settles_for_its_filter() {
        // The board's rates are 1 kHz / (1 + SMPLRT_DIV); a stream's rate must divide them.
        let rates: Vec<u16> = [100, 1000, 500, 333, 8].into_iter().map(stream_rate_hz).collect();
        assert_eq!(rates, [100, 200, 125, 111, 8]);
        let phase = |sample_rate_hz, filter| phase_for(SensorConfig { sample_rate_hz, filter, ..Default::default() });
        let default = phase(100, LowPassFilter::Hz44);
        assert_eq!((default.rate_hz, default.settle, default.samples), (100, 5, 40));
        let slow_filter = phase(1000, LowPassFilter::Hz5);
        assert_eq!((slow_filter.rate_hz, slow_filter.settle, slow_filter.samples), (200, 40, 80));
        assert_eq!(phase(8, LowPassFilter::Hz5).samples, 40, "never fewer than 40");
    }
}
