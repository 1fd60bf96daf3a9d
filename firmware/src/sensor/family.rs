//! What differs between the register families: which family a chip really is (by trying the
//! registers only the MPU-6500 family has), where its accelerometer filter sits, and how its
//! temperature reads.

use embedded_hal_async::i2c::I2c;
use shared::part::{Behaviour, Family, Part, TemperatureFormula};

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
    let mut kept = [false; 2];
    for (keeps, register) in kept.iter_mut().zip([reg::ACCEL_CONFIG2, reg::XA_OFFSET_H_6500]) {
        *keeps = keeps_a_value(bus, address, register).await?;
    }
    let behaviour = Behaviour { accel_config2_kept: kept[0], offsets_at_0x77: kept[1] };
    // NOTE: mixed evidence (one register kept, the other not) trusts a known WHO_AM_I.
    Ok(behaviour.family().or(part.claimed_family()))
}

/// Whether `register` keeps a value written to it; its value is restored either way.
async fn keeps_a_value<I: I2c>(bus: &mut I, address: u8, register: u8) -> Result<bool, Error<I::Error>> {
    let original = read_register(bus, address, register).await?;
    // NOTE: flips bits 0 and 2: A_DLPF_CFG's on ACCEL_CONFIG2, the offset's on XA_OFFSET_H.
    // On XA_OFFSET_H that moves the MPU-6500 family's x output by 625 mg until the restore below,
    // a few transactions later; no sample of that moment is used: a capture or stream starts by
    // resetting the FIFO.
    let probe = original ^ 0b0000_0101;
    write_register(bus, address, register, probe).await?;
    let read_back = read_register(bus, address, register).await?;
    write_register(bus, address, register, original).await?;
    Ok(read_back == probe)
}

/// How a part's TEMP_OUT is re-expressed in the MPU-6050's encoding (raw / 340 + 36.53), so that
/// everything after the driver reads one encoding whatever the part: raw x scale / 2^16 + offset,
/// in integers per sample (worked out once, at the probe).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct TempEncoding {
    scale_q16: i32,
    offset_lsb: i32,
}

impl TempEncoding {
    /// The re-encoding of a part read with `formula`.
    pub(super) fn of(formula: TemperatureFormula) -> Self {
        let target = TemperatureFormula::MPU6050;
        let scale = target.lsb_per_c / formula.lsb_per_c * 65536.0;
        let offset = (formula.offset_c - target.offset_c) * target.lsb_per_c;
        // NOTE: scale is positive; `as` truncates towards zero, so the offset rounds by its sign.
        let offset_lsb = if offset < 0.0 { offset - 0.5 } else { offset + 0.5 } as i32;
        TempEncoding { scale_q16: (scale + 0.5) as i32, offset_lsb }
    }

    /// A raw reading in the MPU-6050's encoding (within half an LSB, 0.0015 degC).
    pub(super) fn apply(self, raw: i16) -> i16 {
        let value = ((i32::from(raw) * self.scale_q16 + 0x8000) >> 16) + self.offset_lsb;
        value.clamp(i32::from(i16::MIN), i32::from(i16::MAX)) as i16
    }
}
