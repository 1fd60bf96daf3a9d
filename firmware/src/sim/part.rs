//! The simulated parts: what distinguishes an MPU-6050 from the MPU-6500 family and its look-alikes
//! at the register level (WHO_AM_I, which registers exist, the temperature formula, the factory
//! trim codes and the self-test response), and a faulty axis to inject.

use shared::part::{accel_offset_g, Family, Part, TemperatureFormula};
use shared::selftest::{self, SELF_TEST_GYRO_RANGE};

use super::physics::PhysicalSample;
use crate::sensor::registers as reg;

/// How far off its factory trim a faulty axis' self-test response is (the `--sim-faulty-axis` fault).
pub const FAULTY_AXIS_ERROR: f32 = 0.20;

/// A simulated part.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SimPart {
    /// What WHO_AM_I (0x75) answers.
    pub who_am_i: u8,
    /// The register map it really has.
    pub family: Family,
    /// How its TEMP_OUT encodes the die temperature.
    pub temperature: TemperatureFormula,
    /// Factory-trim codes, accelerometer x, y, z then gyro x, y, z.
    pub codes: [u8; 6],
    /// Each axis' self-test response over its factory trim (1: exactly the trim).
    pub response_ratio: [f32; 6],
    /// What the accelerometer's x, y, z offset register pairs hold at power-up, as 16-bit words: the
    /// factory's trim, which the physics' offsets already include.
    pub factory_offsets: [i16; 3],
    /// Whether a change of the offset registers moves the output (`false`: a part that keeps what is
    /// written there and ignores it, see [`SimPart::ignoring_offsets`]).
    pub applies_offsets: bool,
}

/// The names `--sim-part` takes, in the order of [`SimPart::by_name`].
pub const SIM_PART_NAMES: [&str; 5] = ["mpu6050", "mpu6500", "mpu9250", "icm20689", "unknown72"];

// NOTE: a healthy part's responses scatter around their trim by a few per cent (the trim was
// measured at the factory, at another temperature and supply); these ratios stay well inside
// every band.
const HEALTHY: [f32; 6] = [1.03, 0.98, 1.02, 0.97, 1.04, 1.01];

impl SimPart {
    /// A genuine MPU-6050.
    pub const fn mpu6050() -> Self {
        SimPart {
            who_am_i: 0x68,
            family: Family::Mpu6050,
            temperature: TemperatureFormula::MPU6050,
            codes: [14, 17, 12, 13, 19, 16],
            response_ratio: HEALTHY,
            // NOTE: factory offsets of a few hundred mg in 1/1024 g, bit 0 (reserved) set on some, as
            // register dumps of real parts show.
            factory_offsets: [-2355, 1201, 1642],
            applies_offsets: true,
        }
    }

    /// An MPU-6500.
    pub const fn mpu6500() -> Self {
        SimPart {
            who_am_i: 0x70,
            family: Family::Mpu6500,
            temperature: TemperatureFormula::MPU6500,
            // NOTE: accelerometer codes 112-125 stand for 0.48-0.55 g, inside the 225-675 mg a healthy
            // part's response lies in (AN-MPU-6500A's criteria B), so that gravity plus a response 20 %
            // too large stays within +-2 g; gyro codes 201-215 for 146-168 deg/s (at least 60).
            codes: [118, 112, 125, 209, 201, 215],
            response_ratio: HEALTHY,
            factory_offsets: [7483, -6928, 10849],
            applies_offsets: true,
        }
    }

    /// An MPU-9250 (its magnetometer, a separate die behind the auxiliary bus, is not modelled).
    pub const fn mpu9250() -> Self {
        SimPart { who_am_i: 0x71, ..SimPart::mpu6500() }
    }

    /// An ICM-20689.
    pub const fn icm20689() -> Self {
        SimPart { who_am_i: 0x98, temperature: TemperatureFormula::ICM20600, ..SimPart::mpu6500() }
    }

    /// A part answering 0x72 (no InvenSense part) that behaves as the MPU-6500 family, as the
    /// modules answering 0x72 do in users' reports.
    pub const fn unknown72() -> Self {
        SimPart { who_am_i: 0x72, ..SimPart::mpu6500() }
    }

    /// The part `--sim-part` names (see [`SIM_PART_NAMES`]).
    pub fn by_name(name: &str) -> Option<Self> {
        let parts = [Self::mpu6050(), Self::mpu6500(), Self::mpu9250(), Self::icm20689(), Self::unknown72()];
        SIM_PART_NAMES.iter().position(|&n| n == name).map(|i| parts[i])
    }

    /// The same part with one self-test axis' response [`FAULTY_AXIS_ERROR`] above its trim:
    /// `axis` 0-2 (x, y, z) on both the accelerometer and the gyro.
    pub fn with_faulty_axis(mut self, axis: usize) -> Self {
        for sensor_axis in [axis, axis + 3] {
            self.response_ratio[sensor_axis] = 1.0 + FAULTY_AXIS_ERROR;
        }
        self
    }

    /// The same part keeping what is written to its accelerometer offset registers but not applying
    /// it to the output: a part whose offset registers are not what its map says.
    pub fn ignoring_offsets(self) -> Self {
        SimPart { applies_offsets: false, ..self }
    }

    /// The part its WHO_AM_I names.
    pub fn part(&self) -> Part {
        Part::from_who_am_i(self.who_am_i)
    }

    /// The self-test response of `axis` (0-5): accelerometer in g, gyro in deg/s.
    pub fn self_test_response(&self, axis: usize) -> f32 {
        let trim_lsb = selftest::factory_trim_lsb(self.family, axis, self.codes[axis]).unwrap_or(0.0);
        let per_unit = if axis < 3 {
            self.family.self_test_range().lsb_per_g()
        } else {
            SELF_TEST_GYRO_RANGE.lsb_per_dps() as f32
        };
        trim_lsb / per_unit * self.response_ratio[axis]
    }

    /// What a self-test register holds, if `address` is one of this family's.
    pub fn self_test_register(&self, address: u8) -> Option<u8> {
        let c = self.codes;
        match (self.family, address) {
            // NOTE: RM-MPU-6000A 4.1: XA_TEST[4:2] in bits 7:5 and XG_TEST in bits 4:0 of 0x0D-0x0F;
            // XA/YA/ZA_TEST[1:0] in bits 5:4, 3:2, 1:0 of 0x10.
            (Family::Mpu6050, 0x0D..=0x0F) => {
                let i = usize::from(address - 0x0D);
                Some(((c[i] >> 2) << 5) | (c[i + 3] & 0x1F))
            }
            (Family::Mpu6050, 0x10) => Some(((c[0] & 3) << 4) | ((c[1] & 3) << 2) | (c[2] & 3)),
            // NOTE: RM-MPU-6500A: SELF_TEST_X/Y/Z_GYRO at 0x00-0x02, _ACCEL at 0x0D-0x0F.
            (Family::Mpu6500, 0x00..=0x02) => Some(c[usize::from(address) + 3]),
            (Family::Mpu6500, 0x0D..=0x0F) => Some(c[usize::from(address - 0x0D)]),
            _ => None,
        }
    }

    /// Whether the part has the register at `address` (writes elsewhere are lost and it reads 0).
    pub fn has_register(&self, address: u8) -> bool {
        match self.family {
            // NOTE: ACCEL_CONFIG2 (0x1D) and the offsets at 0x77-0x7E are the MPU-6500 family's.
            Family::Mpu6050 => !(address == ACCEL_CONFIG2 || (0x77..=0x7E).contains(&address)),
            Family::Mpu6500 => true,
        }
    }
}

/// ACCEL_CONFIG2 (0x1D) of the MPU-6500 family: A_DLPF_CFG in bits 2:0, ACCEL_FCHOICE_B in bit 3.
pub const ACCEL_CONFIG2: u8 = 0x1D;

/// The accelerometer's filter bandwidth on the MPU-6500 family for an ACCEL_CONFIG2 value, in Hz.
///
/// NOTE: RM-MPU-6500A 4.8 (ACCEL_CONFIG2): A_DLPF_CFG 0-7 give 460, 184, 92, 41, 20, 10, 5, 460 Hz
/// (3-dB bandwidth); ACCEL_FCHOICE_B set bypasses it (1.13 kHz). The simulation uses each as the
/// noise bandwidth of a one-pole filter.
pub fn accel_bandwidth_hz(accel_config2: u8) -> f32 {
    const BY_CFG: [f32; 8] = [460.0, 184.0, 92.0, 41.0, 20.0, 10.0, 5.0, 460.0];
    if accel_config2 & 0x08 != 0 {
        1130.0
    } else {
        BY_CFG[usize::from(accel_config2 & 0x07)]
    }
}

impl SimPart {
    /// Adds the self-test response of every axis whose self-test bit is set (bits 7:5 of
    /// ACCEL_CONFIG and GYRO_CONFIG: x, y, z; RM-MPU-6000A 4.4-4.5, the same on the MPU-6500).
    pub fn apply_self_test(&self, accel_config: u8, gyro_config: u8, sample: &mut PhysicalSample) {
        for i in 0..3 {
            let bit = reg::SELF_TEST_BITS & (0x80 >> i);
            if accel_config & bit != 0 {
                sample.accel_g[i] += self.self_test_response(i);
            }
            if gyro_config & bit != 0 {
                sample.gyro_dps[i] += self.self_test_response(i + 3);
            }
        }
    }

    /// Loads the factory offsets into `registers` (a register file at power-up or after a reset).
    pub fn load_factory_offsets(&self, registers: &mut [u8]) {
        for (&high, word) in self.family.accel_offset_registers().iter().zip(self.factory_offsets) {
            let at = usize::from(high);
            registers[at..at + 2].copy_from_slice(&word.to_be_bytes());
        }
    }

    /// Adds to each accelerometer axis what its offset register pair (in `registers`) holds beyond
    /// the factory's value: a step written there moves the output by the same step.
    pub fn apply_offsets(&self, registers: &[u8], sample: &mut PhysicalSample) {
        if !self.applies_offsets {
            return;
        }
        let pairs = self.family.accel_offset_registers().into_iter().zip(self.factory_offsets);
        for (axis, (high, factory)) in pairs.enumerate() {
            let at = usize::from(high);
            let [factory_high, factory_low] = factory.to_be_bytes();
            let step_g = accel_offset_g(registers[at], registers[at + 1]) - accel_offset_g(factory_high, factory_low);
            sample.accel_g[axis] += step_g;
        }
    }

    /// What reading `address` returns when the register file holds `stored` there: the part's own
    /// WHO_AM_I and self-test codes, 0 for a register it does not have.
    pub fn read(&self, address: u8, stored: u8) -> u8 {
        if address == WHO_AM_I {
            return self.who_am_i;
        }
        match self.self_test_register(address) {
            Some(value) => value,
            None if self.has_register(address) => stored,
            None => 0,
        }
    }

    /// The accelerometer noise bandwidth the part's own filter sets, in Hz (`None` on the
    /// MPU-6050, whose model keeps white noise over the Nyquist band).
    pub fn accel_noise_bandwidth_hz(&self, accel_config2: u8) -> Option<f32> {
        (self.family == Family::Mpu6500).then(|| accel_bandwidth_hz(accel_config2))
    }
}

/// WHO_AM_I (0x75), the same address in every family.
const WHO_AM_I: u8 = 0x75;

#[cfg(test)]
mod tests;
