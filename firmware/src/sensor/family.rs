//! What differs between the register families: which family a chip really is (by trying the
//! registers only the MPU-6500 family has), where its accelerometer filter sits, and how its
//! temperature reads.

use embedded_hal_async::i2c::I2c;
use shared::part::{Behaviour, Family, Part, TemperatureFormula};
use shared::protocol::LowPassFilter;

use super::access::{read_register, write_register};
use super::registers as reg;
use super::Error;

/// WHO_AM_I values of no InvenSense part that modules sold as MPU-6050 answer; their registers are
/// tried, so that a working look-alike is run as the family it behaves as.
// NOTE: any other unknown value may be another kind of chip at 0x68 (a DS3231 clock answers
// there): nothing is written to it.
const LOOK_ALIKES: [u8; 2] = [0x72, 0x74];

/// The family a chip at `address` answering `who_am_i` behaves as; `Ok(None)` for a chip that is
/// not one to write to, or whose registers say neither family.
pub(super) async fn family_of<I: I2c>(
    bus: &mut I,
    address: u8,
    who_am_i: u8,
) -> Result<Option<Family>, Error<I::Error>> {
    let part = Part::from_who_am_i(who_am_i);
    if part.claimed_family().is_none() && !LOOK_ALIKES.contains(&who_am_i) {
        return Ok(None);
    }
    let behaviour = Behaviour {
        accel_config2_kept: keeps_a_value(bus, address, reg::ACCEL_CONFIG2).await?,
        offsets_at_0x77: keeps_a_value(bus, address, reg::XA_OFFSET_H_6500).await?,
    };
    // NOTE: mixed evidence (one register kept, the other not) trusts a known WHO_AM_I.
    Ok(behaviour.family().or(part.claimed_family()))
}

/// Whether `register` keeps a value written to it; its value is restored either way.
async fn keeps_a_value<I: I2c>(bus: &mut I, address: u8, register: u8) -> Result<bool, Error<I::Error>> {
    let original = read_register(bus, address, register).await?;
    // NOTE: flips bits 0 and 2: A_DLPF_CFG's on ACCEL_CONFIG2, the offset's on XA_OFFSET_H.
    let probe = original ^ 0b0000_0101;
    write_register(bus, address, register, probe).await?;
    let read_back = read_register(bus, address, register).await?;
    write_register(bus, address, register, original).await?;
    Ok(read_back == probe)
}

/// ACCEL_CONFIG2 (0x1D) of the MPU-6500 family for a filter: A_DLPF_CFG, ACCEL_FCHOICE_B clear.
///
/// NOTE: RM-MPU-6500A 4.8: A_DLPF_CFG 0-6 give 460, 184, 92, 41, 20, 10, 5 Hz; the nearest to the
/// MPU-6050's DLPF_CFG bandwidths (260, 184, 94, 44, 21, 10, 5 Hz) is the same index.
pub(super) fn accel_config2(filter: LowPassFilter) -> u8 {
    match filter {
        LowPassFilter::Hz260 => 0,
        LowPassFilter::Hz184 => 1,
        LowPassFilter::Hz94 => 2,
        LowPassFilter::Hz44 => 3,
        LowPassFilter::Hz21 => 4,
        LowPassFilter::Hz10 => 5,
        LowPassFilter::Hz5 => 6,
    }
}

/// A TEMP_OUT reading of a part read with `formula`, re-expressed in the MPU-6050's encoding
/// (raw / 340 + 36.53), so that everything after the driver reads one encoding whatever the part.
pub(super) fn in_mpu6050_encoding(formula: TemperatureFormula, raw: i16) -> i16 {
    if formula == TemperatureFormula::MPU6050 {
        return raw;
    }
    TemperatureFormula::MPU6050.raw(formula.celsius(raw))
}
