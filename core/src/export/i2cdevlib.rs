//! i2cdevlib's MPU6050 class: the chip's own offset registers (XA_OFFS, XG_OFFS_USR), which add to
//! every reading. The accelerometer's are in +-16 g counts (2048 per g) and hold a factory trim,
//! the gyro's in +-1000 deg/s counts (32.8 per deg/s) (InvenSense, MPU Hardware Offset Registers
//! Application Note); so the export adds to what the chip holds. Offsets only.

use shared::{linalg, AccelRange, GyroRange};

use super::loss::{diagonal, loss, spread, Carried};
use super::statement::{lines, Said};
use super::{text, Export, Source, SLASHES};

/// Counts per g of the accelerometer offset registers (+-16 g format).
const ACCEL_OFFSET_LSB_PER_G: f64 = AccelRange::G16.lsb_per_g() as f64;
/// Counts per deg/s of the gyro offset registers (+-1000 deg/s format).
const GYRO_OFFSET_LSB_PER_DPS: f64 = GyroRange::Dps1000.lsb_per_dps();

const CONVENTION: &[&str] = &[
    "the MPU-6050 adds its offset registers to every reading: reading = raw + register (in the register's units)",
    "accelerometer registers in 2048 counts per g (+-16 g format, whatever the range); gyro registers in 32.8 per deg/s",
    "the accelerometer registers hold a factory trim, which the calibration was measured with: the calls add to it",
    "run them once per power-up, after initialize() (the registers do not survive a power cycle)",
    "no scale and no cross-axis terms: M and G are not carried",
];

const I2CDEVLIB_SAID: Said = Said {
    title: "i2cdevlib MPU6050 (offset registers)",
    convention: CONVENTION,
    carries: "accelerometer and gyro offsets only, rounded to the registers' counts",
    temperature: "the chip's registers have no temperature model: not carried",
};

/// The C++ calls.
pub fn i2cdevlib(source: &Source) -> Export {
    let full = source.full();
    let accel = full.offset_g.map(|v| -(v * ACCEL_OFFSET_LSB_PER_G).round() as i32);
    let gyro = source.gyro_bias_dps().map(|v| {
        mutant!("i2cdevlib-gyro-sign", -(v * GYRO_OFFSET_LSB_PER_DPS).round(), (v * GYRO_OFFSET_LSB_PER_DPS).round())
            as i32
    });
    let carried = Carried {
        matrix: diagonal([1.0; 3]),
        offset_g: accel.map(|v| -f64::from(v) / ACCEL_OFFSET_LSB_PER_G),
        gyro_matrix: diagonal([1.0; 3]),
        gyro_bias_dps: Some(gyro.map(|v| -f64::from(v) / GYRO_OFFSET_LSB_PER_DPS)),
    };
    let loss = loss(&full, &carried);
    let mut body = "\n// MPU6050 mpu; ... mpu.initialize(); then:\n".to_owned();
    for (axis, name) in ["X", "Y", "Z"].iter().enumerate() {
        body.push_str(&format!("mpu.set{name}AccelOffset(mpu.get{name}AccelOffset() + ({}));\n", accel[axis]));
    }
    for (axis, name) in ["X", "Y", "Z"].iter().enumerate() {
        body.push_str(&format!("mpu.set{name}GyroOffset(mpu.get{name}GyroOffset() + ({}));\n", gyro[axis]));
    }
    let mut statement = lines(source, &I2CDEVLIB_SAID, &loss);
    statement.push(imu_zero(source));
    text(statement, &SLASHES, &body, loss)
}

/// What i2cdevlib's IMU_Zero sketch would leave: offsets from one pose (+Z up), chosen so that it reads
/// 0, 0, +1 g there, o' = M^-1 e_z + o - e_z, against the full calibration over the sphere.
fn imu_zero(source: &Source) -> String {
    let full = source.full();
    let up = [0.0, 0.0, 1.0];
    let reading =
        linalg::add(linalg::inverse(&full.matrix).map_or(up, |inverse| linalg::mul_vec(&inverse, up)), full.offset_g);
    let (rms, worst) = spread(&full.matrix, &full.offset_g, &diagonal([1.0; 3]), &linalg::sub(reading, up));
    format!(
        "for comparison, i2cdevlib's IMU_Zero (offsets from one pose, +Z up): {:.4} mg rms, {:.4} mg worst",
        rms * 1e3,
        worst * 1e3
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    // NOTE: the register adds to every reading (reading = raw + register), so a bias b is taken out by
    // -b in the register's 32.8 counts per deg/s: 1.0 deg/s is -33, -0.5 is +16, 0.25 is -8.
    #[test]
    fn the_gyro_offset_lines_add_minus_the_bias_in_the_register_s_counts() {
        let text = String::from_utf8(i2cdevlib(&super::super::example_source()).bytes).unwrap();
        for line in [
            "mpu.setXGyroOffset(mpu.getXGyroOffset() + (-33));",
            "mpu.setYGyroOffset(mpu.getYGyroOffset() + (16));",
            "mpu.setZGyroOffset(mpu.getZGyroOffset() + (-8));",
        ] {
            assert!(text.lines().any(|l| l == line), "no `{line}` in\n{text}");
        }
    }
}
