//! The MultiWii family's command lines: Betaflight (`acc_calibration`, offsets only) and INAV
//! (`acczero`, `accgain`: offsets and a scale per axis), both in the firmware's raw counts.

use shared::linalg::Vec3;

use super::loss::{best_diagonal, diagonal, loss, Carried};
use super::statement::{lines, Said};
use super::{text, Export, Source, HASH};

/// Counts per g Betaflight's MPU-6050 driver reads at (acc_1G = 512 * 4: +-16 g).
const BETAFLIGHT_LSB_PER_G: f64 = 2048.0;
/// Counts per g INAV's MPU-6050 driver reads at (acc_1G = 512 * 8: +-8 g).
const INAV_LSB_PER_G: f64 = 4096.0;
/// INAV's accgain for a scale of 1 (accgain / 4096 multiplies the reading).
const INAV_GAIN_ONE: f64 = 4096.0;

/// Offsets only, in whole counts at `lsb_per_g`, with an optional per-axis scale; no gyro bias kept.
fn carried(source: &Source, lsb_per_g: f64, scale: Vec3<f64>) -> (Carried, [i32; 3]) {
    let full = source.full();
    let counts = full
        .offset_g
        .map(|v| mutant!("multiwii-offset-sign", (v * lsb_per_g).round(), -(v * lsb_per_g).round()) as i32);
    let carried = Carried {
        matrix: diagonal(scale),
        offset_g: counts.map(|v| f64::from(v) / lsb_per_g),
        gyro_matrix: diagonal([1.0; 3]),
        gyro_bias_dps: None,
    };
    (carried, counts)
}

const BETAFLIGHT_CONVENTION: &[&str] = &[
    "Betaflight: a = m - acc_calibration per axis, in raw counts at 2048 per g (its MPU-6050 driver's acc_1G, +-16 g)",
    "no scale and no cross-axis terms: M is not carried",
    "the fourth value (1) marks the calibration as done; the gyro bias is measured again at every boot",
];

const BETAFLIGHT_SAID: Said = Said {
    title: "Betaflight (CLI)",
    convention: BETAFLIGHT_CONVENTION,
    carries: "accelerometer offsets only (no scale, no gyro bias: Betaflight measures it at boot)",
    temperature: "Betaflight has no temperature model: not carried",
    lossy: true,
};

/// The Betaflight CLI commands.
pub fn betaflight(source: &Source) -> Export {
    let (carried, counts) = carried(source, BETAFLIGHT_LSB_PER_G, [1.0; 3]);
    let loss = loss(&source.full(), &carried);
    let body = format!("set acc_calibration = {},{},{},1\nsave\n", counts[0], counts[1], counts[2]);
    text(lines(source, &BETAFLIGHT_SAID, &loss), &HASH, &body, loss)
}

const INAV_CONVENTION: &[&str] = &[
    "INAV: a = (m - acczero) * accgain / 4096 per axis, in raw counts at 4096 per g (its MPU-6050 driver's acc_1G, +-8 g)",
    "the off-diagonal terms of M (cross-axis and misalignment) have no setting: the scale is the per-axis least-squares best",
    "the gyro bias is measured again at every boot",
];

const INAV_SAID: Said = Said {
    title: "INAV (CLI)",
    convention: INAV_CONVENTION,
    carries: "accelerometer offsets and a scale per axis (no cross-axis terms, no gyro bias: INAV measures it at boot)",
    temperature: "INAV has no temperature model: not carried",
    lossy: true,
};

/// The INAV CLI commands.
pub fn inav(source: &Source) -> Export {
    let gains = best_diagonal(&source.full().matrix).map(|s| (s * INAV_GAIN_ONE).round() as i32);
    let (carried, counts) = carried(source, INAV_LSB_PER_G, gains.map(|g| f64::from(g) / INAV_GAIN_ONE));
    let loss = loss(&source.full(), &carried);
    let mut body = String::new();
    for (axis, name) in ["x", "y", "z"].iter().enumerate() {
        body.push_str(&format!("set acczero_{name} = {}\n", counts[axis]));
    }
    for (axis, name) in ["x", "y", "z"].iter().enumerate() {
        body.push_str(&format!("set accgain_{name} = {}\n", gains[axis]));
    }
    body.push_str("save\n");
    text(lines(source, &INAV_SAID, &loss), &HASH, &body, loss)
}

#[cfg(test)]
mod tests {
    use super::*;

    // NOTE: Betaflight subtracts acc_calibration from the raw reading (sensors/acceleration.c,
    // applyAccelerationTrims: accADC -= accZero), in counts at 2048 per g: the offset itself, rounded.
    #[test]
    fn betaflight_s_acc_calibration_is_the_offset_in_its_counts() {
        let source = super::super::example_source();
        let text = String::from_utf8(betaflight(&source).bytes).unwrap();
        let counts = source.full().offset_g.map(|o| (o * 2048.0).round() as i32);
        let line = format!("set acc_calibration = {},{},{},1", counts[0], counts[1], counts[2]);
        assert!(text.lines().any(|l| l == line), "no `{line}` in\n{text}");
        // The session's sensor offset is +0.03, -0.01, -0.08 g: the signs show.
        assert!(counts[0] > 20 && counts[2] < -100, "{counts:?}");
    }
}
