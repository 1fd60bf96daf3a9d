//! One phase of a self-test attempt: self-test off or on, the output settled, then averaged.

use firmware::sensor::registers::{ACCEL_CONFIG, FULL_SCALE_SHIFT, GYRO_CONFIG, GYRO_LSB_PER_DPS, SELF_TEST_BITS};
use shared::part::Family;
use shared::selftest::SELF_TEST_GYRO_RANGE;

use super::SelfTestError;
use crate::link::{Client, Port};
use crate::still::StillPhase;

/// Samples averaged in each phase.
///
/// NOTE: AN-MPU-6500A averages 200 samples each side; at 200 Hz that is a second, over which a
/// still board's mean is known to about 0.3 mg and 0.005 deg/s, well below 1 % of any response.
pub const PHASE_SAMPLES: usize = 200;
/// Samples passed over after the registers change, while the output settles.
///
/// NOTE: the application note waits 20 ms after switching self-test on; 10 samples at 200 Hz are
/// 50 ms, which also covers the 94 Hz filter's step response.
const SETTLE_SAMPLES: usize = 10;

/// The three phases of an attempt, in order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PhaseName {
    /// Self-test off, before.
    OffBefore,
    /// Self-test on.
    On,
    /// Self-test off, after.
    OffAfter,
}

impl PhaseName {
    /// Every phase, in order.
    pub const ALL: [PhaseName; 3] = [PhaseName::OffBefore, PhaseName::On, PhaseName::OffAfter];

    /// The phase's name in a message.
    pub fn label(self) -> &'static str {
        match self {
            PhaseName::OffBefore => "self-test off (before)",
            PhaseName::On => "self-test on",
            PhaseName::OffAfter => "self-test off (after)",
        }
    }
}

/// The means of an attempt, in LSB at the self-test ranges.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhaseMeans {
    /// The two off phases averaged.
    pub off_lsb: [f32; 6],
    /// The on phase.
    pub on_lsb: [f32; 6],
}

/// A phase to run on a board of `family` streaming at `rate_hz`, its accelerometer configured as
/// ACCEL_CONFIG `accel_config` (the self-test range, self-test off) holds.
pub struct Phase {
    pub family: Family,
    pub name: PhaseName,
    pub rate_hz: u16,
    pub accel_config: u8,
}

impl Phase {
    /// Sets the phase's registers and averages it: the mean per axis in LSB, or why the board moved.
    pub fn run<P: Port>(&self, client: &mut Client<P>) -> Result<Result<[f32; 6], String>, SelfTestError> {
        let (gyro_config, accel_config) = self.registers();
        client.write_register(GYRO_CONFIG, gyro_config)?;
        client.write_register(ACCEL_CONFIG, accel_config)?;
        // NOTE: the board's gyro figures are four times the +-250 deg/s rates (it converts at +-1000).
        let gyro_dps_per_reported = f64::from(GYRO_LSB_PER_DPS / SELF_TEST_GYRO_RANGE.lsb_per_dps() as f32);
        let phase = StillPhase {
            label: self.name.label(),
            rate_hz: self.rate_hz,
            settle: SETTLE_SAMPLES,
            samples: PHASE_SAMPLES,
            gyro_dps_per_reported,
        };
        Ok(phase.mean(client)?.map(|mean| self.to_lsb(mean)))
    }

    /// GYRO_CONFIG and ACCEL_CONFIG for this phase: the trim's ranges, self-test bits on or off.
    fn registers(&self) -> (u8, u8) {
        let bits = if self.name == PhaseName::On { SELF_TEST_BITS } else { 0 };
        (bits | SELF_TEST_GYRO_RANGE.fs_sel() << FULL_SCALE_SHIFT, bits | (self.accel_config & !SELF_TEST_BITS))
    }

    /// A mean in g and deg/s as the board converts them, back to LSB at the self-test ranges.
    ///
    /// NOTE: the board converts with the range it was configured for (the self-test range) and the
    /// gyro's +-1000 deg/s sensitivity; the gyro ran at +-250 deg/s, so its count is the reported
    /// rate times the board's factor.
    fn to_lsb(&self, mean: [f64; 6]) -> [f32; 6] {
        let lsb_per_g = f64::from(self.family.self_test_range().lsb_per_g());
        core::array::from_fn(|axis| {
            let per_unit = if axis < 3 { lsb_per_g } else { f64::from(GYRO_LSB_PER_DPS) };
            (mean[axis] * per_unit) as f32
        })
    }
}
