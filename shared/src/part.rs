//! Which sensor answered: the part named by its WHO_AM_I, the register family it behaves as, and
//! what differs between families (the temperature formula, where the accelerometer's low-pass
//! filter and offset registers sit).
//!
//! Many modules sold as "MPU-6050" carry other parts. The WHO_AM_I register (0x75) names the part
//! the chip claims to be; its behaviour (which registers exist) names the family it really
//! belongs to, and the two are compared so that a part that claims one thing and does another is
//! named as such.

use serde::{Deserialize, Serialize};

/// A register family: parts that share a register map for everything accelcal uses.
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq, Eq)]
pub enum Family {
    /// MPU-6000 / MPU-6050 (RM-MPU-6000A-00): the accelerometer's low-pass filter is CONFIG's
    /// DLPF_CFG, offsets at 0x06-0x0B, 5-bit self-test codes in 0x0D-0x10.
    Mpu6050,
    /// MPU-6500 and its descendants (MPU-9250/9255, ICM-206xx; RM-MPU-6500A-00): the accelerometer
    /// has its own filter in ACCEL_CONFIG2 (0x1D), offsets at 0x77-0x7E, 8-bit self-test codes in
    /// 0x00-0x02 (gyro) and 0x0D-0x0F (accelerometer).
    Mpu6500,
}

impl Family {
    /// The accelerometer's x, y, z offset registers, each the high byte of a big-endian pair whose
    /// low byte follows it.
    ///
    /// NOTE: MPU-6050: XA/YA/ZA_OFFS_H at 0x06, 0x08, 0x0A, not in RM-MPU-6000A rev 4.2 but in
    /// InvenSense's "MPU Hardware Offset Registers" application note (AN-XX-XXXX-XX rev 1.0,
    /// 2014-02-21); MPU-6500 family: XA/YA/ZA_OFFSET_H at 0x77, 0x7A, 0x7D ("Registers 119, 120,
    /// 122, 123, 125, 126 - Accelerometer Offset Registers", RM-MPU-6500A-00 rev 2.1 and
    /// RM-MPU-9250A-00 rev 1.4 section 4.39).
    pub const fn accel_offset_registers(self) -> [u8; 3] {
        match self {
            Family::Mpu6050 => [0x06, 0x08, 0x0A],
            Family::Mpu6500 => [0x77, 0x7A, 0x7D],
        }
    }
}

/// The offset an accelerometer offset register pair adds to the output, in g, whatever the range.
///
/// NOTE: RM-MPU-9250A-00 rev 1.4 4.39 (and RM-MPU-6500A-00's registers 119-126): XA_OFFS[14:7] in
/// the high byte, XA_OFFS[6:0] in bits 7:1 of the low byte, "+/- 16g Offset cancellation in all Full
/// Scale modes, 15 bit 0.98-mg steps": a signed 15-bit value in 1/1024 g, bit 0 reserved. The
/// MPU-6050's pairs at 0x06-0x0B hold the same format (the offset-register application note).
pub fn accel_offset_g(high: u8, low: u8) -> f32 {
    f32::from(i16::from_be_bytes([high, low]) >> 1) / 1024.0
}

/// A part as named by its WHO_AM_I.
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq, Eq)]
pub enum Part {
    /// MPU-6000 or MPU-6050 (0x68; the MPU-9150's accelerometer and gyro answer the same).
    Mpu6050,
    /// MPU-6500 (0x70).
    Mpu6500,
    /// MPU-9250 (0x71).
    Mpu9250,
    /// MPU-9255 (0x73).
    Mpu9255,
    /// ICM-20689 (0x98).
    Icm20689,
    /// ICM-20608-G (0xAF) or ICM-20608-D (0xAE).
    Icm20608,
    /// ICM-20602 (0x12).
    Icm20602,
    /// ICM-20601 (0xAC).
    Icm20601,
    /// A WHO_AM_I no InvenSense/TDK part of these families answers (0x72 and 0x74 are common on
    /// modules sold as MPU-6050).
    Unknown(u8),
}

/// WHO_AM_I values of the known parts.
// NOTE: from the parts' register maps (RM-MPU-6000A 4.33: 0x68; RM-MPU-6500A 4.3x: 0x70;
// RM-MPU-9250A: 0x71) and, for the others, the table of WHO_AM_I values ArduPilot's Invensense
// driver recognises (AP_InertialSensor_Invensense_registers.h: 9255 0x73, 20689 0x98, 20608 0xAE/0xAF,
// 20602 0x12, 20601 0xAC).
const KNOWN: [(u8, Part); 9] = [
    (0x68, Part::Mpu6050),
    (0x70, Part::Mpu6500),
    (0x71, Part::Mpu9250),
    (0x73, Part::Mpu9255),
    (0x98, Part::Icm20689),
    (0xAE, Part::Icm20608),
    (0xAF, Part::Icm20608),
    (0x12, Part::Icm20602),
    (0xAC, Part::Icm20601),
];

impl Part {
    /// The part a WHO_AM_I value names.
    pub fn from_who_am_i(who_am_i: u8) -> Part {
        KNOWN.iter().find(|(value, _)| *value == who_am_i).map_or(Part::Unknown(who_am_i), |&(_, part)| part)
    }

    /// The part's name as its maker writes it ("unknown" for an unknown part).
    pub fn name(self) -> &'static str {
        match self {
            Part::Mpu6050 => "MPU-6050",
            Part::Mpu6500 => "MPU-6500",
            Part::Mpu9250 => "MPU-9250",
            Part::Mpu9255 => "MPU-9255",
            Part::Icm20689 => "ICM-20689",
            Part::Icm20608 => "ICM-20608",
            Part::Icm20602 => "ICM-20602",
            Part::Icm20601 => "ICM-20601",
            Part::Unknown(_) => "unknown",
        }
    }

    /// The family the part belongs to by its datasheet; `None` for an unknown part.
    pub fn claimed_family(self) -> Option<Family> {
        match self {
            Part::Mpu6050 => Some(Family::Mpu6050),
            Part::Unknown(_) => None,
            _ => Some(Family::Mpu6500),
        }
    }

    /// How the part's TEMP_OUT converts to degC when it behaves as `family`: the part's own
    /// formula, or the family's for an unknown part.
    pub fn temperature(self, family: Family) -> TemperatureFormula {
        match (self, family) {
            (Part::Mpu6050, _) | (Part::Unknown(_), Family::Mpu6050) => TemperatureFormula::MPU6050,
            (Part::Icm20689 | Part::Icm20608 | Part::Icm20602 | Part::Icm20601, _) => TemperatureFormula::ICM20600,
            _ => TemperatureFormula::MPU6500,
        }
    }
}

/// degC = raw / `lsb_per_c` + `offset_c`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TemperatureFormula {
    /// Sensitivity, in LSB per degC.
    pub lsb_per_c: f32,
    /// The temperature a raw reading of 0 stands for, in degC.
    pub offset_c: f32,
}

impl TemperatureFormula {
    /// MPU-6000/6050: raw / 340 + 36.53 (RM-MPU-6000A 4.18).
    pub const MPU6050: Self = TemperatureFormula { lsb_per_c: 340.0, offset_c: 36.53 };
    /// MPU-6500/9250/9255: raw / 333.87 + 21 (PS-MPU-6500A 3.4.2 and RM-MPU-6500A 4.22:
    /// sensitivity 333.87 LSB/degC, 0 LSB at 21 degC; PS-MPU-9250A the same).
    // NOTE: ArduPilot uses 21 + raw / 340 for the MPU-9250 and the MPU-6050's formula for the
    // MPU-6500; the datasheets' sensitivity is 333.87, which is what is used here.
    pub const MPU6500: Self = TemperatureFormula { lsb_per_c: 333.87, offset_c: 21.0 };
    /// ICM-20689/20608/20602/20601: raw / 326.8 + 25 (ICM-20689 datasheet DS-000143 3.4; ArduPilot
    /// uses the same for the ICM-2060x).
    pub const ICM20600: Self = TemperatureFormula { lsb_per_c: 326.8, offset_c: 25.0 };

    /// The temperature a raw reading stands for, in degC.
    pub fn celsius(self, raw: i16) -> f32 {
        f32::from(raw) / self.lsb_per_c + self.offset_c
    }

    /// The raw reading of a temperature in degC (rounded, clamped to i16).
    pub fn raw(self, temp_c: f32) -> i16 {
        let lsb = (temp_c - self.offset_c) * self.lsb_per_c;
        let rounded = if lsb >= 0.0 { lsb + 0.5 } else { lsb - 0.5 };
        rounded.clamp(f32::from(i16::MIN), f32::from(i16::MAX)) as i16
    }
}

/// What the chip did when its family's registers were tried (written, read back, restored).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Behaviour {
    /// ACCEL_CONFIG2 (0x1D) kept a value written to it.
    pub accel_config2_kept: bool,
    /// The MPU-6500 family's accelerometer offset register (XA_OFFSET_H, 0x77) kept a value.
    pub offsets_at_0x77: bool,
}

impl Behaviour {
    /// The family these registers belong to; `None` when the evidence disagrees with itself.
    pub fn family(self) -> Option<Family> {
        match (self.accel_config2_kept, self.offsets_at_0x77) {
            (true, true) => Some(Family::Mpu6500),
            (false, false) => Some(Family::Mpu6050),
            _ => None,
        }
    }
}

/// A part named by its WHO_AM_I and its family as it behaves.
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq, Eq)]
pub struct Identification {
    /// The part its WHO_AM_I names.
    pub part: Part,
    /// The family it behaves as (what the driver configures it as).
    pub family: Family,
}

impl Identification {
    /// Whether the behaviour contradicts what the WHO_AM_I claims (an unknown part claims nothing).
    pub fn contradicts_who_am_i(self) -> bool {
        self.part.claimed_family().is_some_and(|claimed| claimed != self.family)
    }

    /// The temperature formula to read this chip with.
    pub fn temperature(self) -> TemperatureFormula {
        self.part.temperature(self.family)
    }
}

#[cfg(test)]
mod tests;
