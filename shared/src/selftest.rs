//! The datasheet self-test's arithmetic: the factory-trim codes out of their registers, the factory
//! trim (FT) each code stands for, and each axis's response judged against it by its family's band.
//!
//! The procedure (RM-MPU-6000A 4.1; AN-MPU-6500A / AN-MPU-9250A-03 for the MPU-6500 family):
//! with the ranges the trim assumes, the self-test response (STR) is the output with self-test on
//! minus the output with it off; the change from factory trim is (STR - FT) / FT. The board runs
//! the procedure; this module turns its raw numbers into the verdict, the same on chip and host.

use serde::{Deserialize, Serialize};

use crate::part::Family;
use crate::{AccelRange, GyroRange};

/// The six axes, accelerometer first, in the order of every array here.
pub const AXIS_NAMES: [&str; 6] = ["accel_x", "accel_y", "accel_z", "gyro_x", "gyro_y", "gyro_z"];

/// The gyro range every family's gyro trim assumes: +-250 deg/s, 131 LSB per deg/s (PS-MPU-6000A
/// 6.1; PS-MPU-6500A 3.1).
pub const SELF_TEST_GYRO_RANGE: GyroRange = GyroRange::Dps250;

/// What the board measured: the trim codes and the mean outputs, in LSB at [`Family::self_test_range`]
/// and +-250 deg/s.
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq)]
pub struct SelfTestRaw {
    /// The family the procedure ran as.
    pub family: Family,
    /// The factory-trim codes, accelerometer x, y, z then gyro x, y, z (5-bit on the MPU-6050
    /// family, 8-bit on the MPU-6500 family; 0 means none was stored).
    pub codes: [u8; 6],
    /// Mean output with self-test off (before and after averaged), per axis, in LSB.
    pub off_lsb: [f32; 6],
    /// Mean output with self-test on, per axis, in LSB.
    pub on_lsb: [f32; 6],
    /// How many times the procedure ran (more than 1: the board moved and it was repeated).
    pub attempts: u8,
}

/// A self-test as the board keeps it in flash beside its calibration (one, the latest): what a
/// later run, on any host, compares with, and what a certificate quotes.
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq)]
pub struct StoredSelfTest {
    /// When it ran, in seconds since 1970 UTC (the host's clock: the board has none).
    pub unix_time_s: u32,
    /// What was measured; the verdicts follow from it ([`evaluate`]).
    pub raw: SelfTestRaw,
}

/// Largest [`SelfTestRecord`], in bytes (a [`StoredSelfTest`] takes at most 61).
pub const SELF_TEST_RECORD_LEN: usize = 64;

/// A [`StoredSelfTest`] as the host encodes it (postcard) and the board keeps it, unread.
///
/// NOTE: the board never decodes it: reading the record's fields on the chip cost the Pico's image
/// about 900 bytes of serde code, which it does not have; bytes cost a loop.
pub type SelfTestRecord = heapless::Vec<u8, SELF_TEST_RECORD_LEN>;

impl StoredSelfTest {
    /// The record the board keeps.
    pub fn record(&self) -> SelfTestRecord {
        let mut bytes = [0u8; SELF_TEST_RECORD_LEN];
        // NOTE: cannot fail: the largest encoding (a 5-byte time, 56 bytes of raw) fits.
        let used = postcard::to_slice(self, &mut bytes).map_or(0, |used| used.len());
        SelfTestRecord::from_slice(&bytes[..used]).unwrap_or_default()
    }

    /// The self-test a record holds; `None` when it is not one.
    pub fn from_record(record: &[u8]) -> Option<Self> {
        postcard::from_bytes(record).ok()
    }
}

/// One axis's verdict. Accelerometer values in g, gyro values in deg/s.
#[derive(Serialize, Debug, Clone, Copy, PartialEq)]
pub struct AxisVerdict {
    /// Which axis, as in [`AXIS_NAMES`].
    pub axis: &'static str,
    /// The self-test response (on minus off).
    pub response: f32,
    /// The factory trim; `None` when the code is 0 and the absolute window judged instead.
    pub factory_trim: Option<f32>,
    /// (response - trim) / trim in percent; `None` with no trim.
    pub deviation_percent: Option<f32>,
    /// Whether the response lies in accelcal's band, the MPU-6050's +-14 % on every family
    /// ([`ACCELCAL_BAND_PERCENT`]), or in the absolute window.
    pub passed: bool,
    /// Whether it lies in the family's own datasheet band (or the absolute window).
    pub datasheet_passed: bool,
    /// The raw factory-trim code.
    pub code: u8,
}

impl Family {
    /// The accelerometer range the family's accelerometer trim assumes: +-8 g on the MPU-6050
    /// (RM-MPU-6000A 4.1), +-2 g on the MPU-6500 family (RM-MPU-6500A 4.x: ST_OTP at FS = 0).
    pub fn self_test_range(self) -> AccelRange {
        match self {
            Family::Mpu6050 => AccelRange::G8,
            Family::Mpu6500 => AccelRange::G2,
        }
    }
}

/// The MPU-6050's 5-bit codes from SELF_TEST_X, _Y, _Z, _A (0x0D-0x10), accelerometer then gyro.
///
/// NOTE: RM-MPU-6000A 4.1: XA_TEST[4:2] is bits 7:5 of SELF_TEST_X, XA_TEST[1:0] bits 5:4 of
/// SELF_TEST_A (YA 3:2, ZA 1:0); XG_TEST[4:0] is bits 4:0 of SELF_TEST_X. The low bits must be
/// masked: bits 7:6 of SELF_TEST_A are reserved.
pub fn mpu6050_codes(registers: [u8; 4]) -> [u8; 6] {
    let accel = |i: usize| ((registers[i] >> 5) << 2) | ((registers[3] >> (4 - 2 * i)) & 0b11);
    let gyro = |i: usize| registers[i] & 0b1_1111;
    [accel(0), accel(1), accel(2), gyro(0), gyro(1), gyro(2)]
}

/// The MPU-6500 family's 8-bit codes: SELF_TEST_X/Y/Z_ACCEL (0x0D-0x0F) then _GYRO (0x00-0x02).
pub fn mpu6500_codes(accel: [u8; 3], gyro: [u8; 3]) -> [u8; 6] {
    [accel[0], accel[1], accel[2], gyro[0], gyro[1], gyro[2]]
}

/// The factory trim of `axis` (0-5) for `code`, in LSB at the self-test ranges; `None` for code 0.
pub fn factory_trim_lsb(family: Family, axis: usize, code: u8) -> Option<f32> {
    if code == 0 {
        return None;
    }
    let steps = f32::from(code) - 1.0;
    Some(match (family, axis) {
        // NOTE: RM-MPU-6000A 4.1: FT[Xa] = 4096 * 0.34 * (0.92 / 0.34)^((XA_TEST - 1) / (2^5 - 2)).
        (Family::Mpu6050, 0..=2) => 4096.0 * 0.34 * libm::powf(0.92 / 0.34, steps / 30.0),
        // NOTE: RM-MPU-6000A 4.1: FT[Xg] = 25 * 131 * 1.046^(XG_TEST - 1), and FT[Yg] negative.
        (Family::Mpu6050, 4) => -25.0 * 131.0 * libm::powf(1.046, steps),
        (Family::Mpu6050, _) => 25.0 * 131.0 * libm::powf(1.046, steps),
        // NOTE: RM-MPU-6500A (and RM-MPU-9250A) 4.x: ST_OTP = (2620 / 2^FS) * 1.01^(ST_code - 1), FS = 0.
        (Family::Mpu6500, _) => 2620.0 * libm::powf(1.01, steps),
    })
}

/// The verdicts of all six axes.
pub fn evaluate(raw: &SelfTestRaw) -> [AxisVerdict; 6] {
    core::array::from_fn(|axis| verdict(raw, axis))
}

/// Whether every axis passed accelcal's band.
pub fn passed(verdicts: &[AxisVerdict; 6]) -> bool {
    verdicts.iter().all(|v| v.passed)
}

/// Whether every axis passed its family's datasheet band.
pub fn datasheet_passed(verdicts: &[AxisVerdict; 6]) -> bool {
    verdicts.iter().all(|v| v.datasheet_passed)
}

fn verdict(raw: &SelfTestRaw, axis: usize) -> AxisVerdict {
    let per_unit = lsb_per_unit(raw.family, axis);
    let response = (raw.on_lsb[axis] - raw.off_lsb[axis]) / per_unit;
    let code = raw.codes[axis];
    let factory_trim = factory_trim_lsb(raw.family, axis, code).map(|ft| ft / per_unit);
    let deviation_percent = factory_trim.map(|ft| (response - ft) / ft * 100.0);
    let (passed, datasheet_passed) = match deviation_percent {
        Some(deviation) => (deviation.abs() <= ACCELCAL_BAND_PERCENT, in_band(raw.family, axis, deviation)),
        None => {
            let inside = in_absolute_window(raw.family, axis, response);
            (inside, inside)
        }
    };
    AxisVerdict { axis: AXIS_NAMES[axis], response, factory_trim, deviation_percent, passed, datasheet_passed, code }
}

/// LSB per g (accelerometer) or per deg/s (gyro) at the self-test ranges.
fn lsb_per_unit(family: Family, axis: usize) -> f32 {
    if axis < 3 {
        family.self_test_range().lsb_per_g()
    } else {
        SELF_TEST_GYRO_RANGE.lsb_per_dps() as f32
    }
}

/// accelcal's band on the change from factory trim, in percent, on every family.
///
/// NOTE: PS-MPU-6000A 6.1 and 6.2 give the MPU-6050's self-test response relative to factory trim
/// as -14 to +14 %. The MPU-6500 family's application note (AN-MPU-6500A, AN-MPU-9250A-03) allows
/// +-50 % on the accelerometer and anything from -50 % up on the gyro, so a response 20 % off its
/// trim passes there. The factory trim is the same kind of measurement on both families, and a
/// healthy part of either lands within a few per cent of it; accelcal judges every family by the
/// MPU-6050's band, so that a 20 %-off axis fails on every part, and reports the family's own
/// verdict beside it ([`AxisVerdict::datasheet_passed`]).
pub const ACCELCAL_BAND_PERCENT: f32 = 14.0;

/// The family's own datasheet band on the change from factory trim, in percent.
fn in_band(family: Family, axis: usize, deviation_percent: f32) -> bool {
    match (family, axis) {
        // NOTE: PS-MPU-6000A 6.1 and 6.2: self-test response relative to factory trim, -14 to +14 %.
        (Family::Mpu6050, _) => deviation_percent.abs() <= ACCELCAL_BAND_PERCENT,
        // NOTE: the MPU-6500 family's self-test criteria (AN-MPU-6500A / AN-MPU-9250A-03, as
        // InvenSense's Embedded MotionDriver 6.12 implements them): accelerometer within +-50 % of
        // ST_OTP; gyro response at least 50 % of ST_OTP, with no upper limit.
        (Family::Mpu6500, 0..=2) => deviation_percent.abs() <= 50.0,
        (Family::Mpu6500, _) => deviation_percent >= -50.0,
    }
}

/// The absolute window for an axis whose code is 0 (no factory trim stored).
fn in_absolute_window(family: Family, axis: usize, response: f32) -> bool {
    let magnitude = response.abs();
    match (family, axis) {
        // NOTE: the MPU-6500 family's criteria B: accelerometer 225-675 mg, gyro at least 60 deg/s.
        (Family::Mpu6500, 0..=2) => (0.225..=0.675).contains(&magnitude),
        (Family::Mpu6500, _) => magnitude >= 60.0,
        // NOTE: the MPU-6050 datasheet gives no absolute window. The trim formulas span codes 1-31:
        // accelerometer 0.34-0.92 g, gyro 25-96.6 deg/s; that span widened by the +-14 % band is
        // the window a healthy part's response lies in, whatever its code.
        (Family::Mpu6050, 0..=2) => (0.34 * 0.86..=0.92 * 1.14).contains(&magnitude),
        (Family::Mpu6050, _) => (25.0 * 0.86..=96.6 * 1.14).contains(&magnitude),
    }
}

/// A board that moved between the two self-test-off phases more than this, in g, spoils the
/// baseline the response is measured from, and the procedure is repeated.
///
/// NOTE: a 50 mg change of the baseline alone is 5-15 % of the accelerometer responses (0.34-0.92 g
/// at +-8 g), against a +-14 % band; 10 mg keeps the error below 3 %.
pub const MAX_BASELINE_SHIFT_G: f32 = 0.010;
/// The same for the gyro, in deg/s: a turn of a degree a second is 1-4 % of a 25-97 deg/s response.
pub const MAX_BASELINE_SHIFT_DPS: f32 = 1.0;

/// Whether the board moved between two self-test-off means (LSB at the self-test ranges).
pub fn baseline_moved(family: Family, before_lsb: &[f32; 6], after_lsb: &[f32; 6]) -> bool {
    (0..6).any(|axis| {
        let shift = (after_lsb[axis] - before_lsb[axis]).abs() / lsb_per_unit(family, axis);
        shift > if axis < 3 { MAX_BASELINE_SHIFT_G } else { MAX_BASELINE_SHIFT_DPS }
    })
}

#[cfg(test)]
mod tests;
