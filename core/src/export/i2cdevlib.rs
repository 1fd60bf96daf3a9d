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
    "bit 0 of each accelerometer register is reserved and keeps what it holds: the counts added are even, a step of 2 \
     counts (0.98 mg) (InvenSense, MPU Hardware Offset Registers Application Note; i2cdevlib's own calibration masks \
     with 0xFFFE)",
    "a header to include at file scope; call its function once per power-up, after initialize() (the registers do not \
     survive a power cycle)",
    "no scale and no cross-axis terms: M and G are not carried",
];

const I2CDEVLIB_SAID: Said = Said {
    title: "i2cdevlib MPU6050 (offset registers)",
    convention: CONVENTION,
    carries: "accelerometer offsets to 2 counts (bit 0 kept) and gyro offsets to 1 count of the registers",
    temperature: "the chip's registers have no temperature model: not carried",
    lossy: true,
};

/// The counts added to each accelerometer register: even, so that the reserved bit 0 keeps what it
/// holds (InvenSense, MPU Hardware Offset Registers Application Note).
fn accel_counts(offset_g: [f64; 3]) -> [i32; 3] {
    offset_g.map(|v| 2 * (-v * ACCEL_OFFSET_LSB_PER_G / 2.0).round() as i32)
}

/// The C++ header: a function that adds the offsets through the sketch's MPU6050 object.
pub fn i2cdevlib(source: &Source) -> Export {
    let full = source.full();
    let accel = accel_counts(full.offset_g);
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
    let mut statement = lines(source, &I2CDEVLIB_SAID, &loss);
    statement.push(imu_zero(source));
    text(statement, &SLASHES, &header(object(source), accel, gyro), loss)
}

/// The name of the sketch's MPU6050 object: `accelgyro` where the stream came from i2cdevlib's
/// MPU6050_raw example, which names it so; else `mpu`.
fn object(source: &Source) -> &'static str {
    let printed = source.readings.printed.as_ref();
    if printed.and_then(|p| p.dialect.as_deref()) == Some("i2cdevlib") {
        "accelgyro"
    } else {
        "mpu"
    }
}

/// The header's text, with `object` the name of the sketch's MPU6050.
fn header(object: &str, accel: [i32; 3], gyro: [i32; 3]) -> String {
    let mut body = format!(
        "\n#ifndef ACCELCAL_I2CDEVLIB_H\n#define ACCELCAL_I2CDEVLIB_H\n\n#include \"MPU6050.h\"\n\n\
         // In setup(), after {object}.initialize(): accelcal_add_offsets({object});\n\
         static inline void accelcal_add_offsets(MPU6050 &{object}) {{\n"
    );
    for (kind, counts) in [("Accel", accel), ("Gyro", gyro)] {
        for (axis, name) in ["X", "Y", "Z"].iter().enumerate() {
            body.push_str(&format!(
                "    {object}.set{name}{kind}Offset({object}.get{name}{kind}Offset() + ({}));\n",
                counts[axis]
            ));
        }
    }
    body.push_str("}\n\n#endif // ACCELCAL_I2CDEVLIB_H\n");
    body
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
    use super::super::Readings;
    use super::*;
    use crate::stream::units::AccelUnit;

    // NOTE: the register adds to every reading (reading = raw + register), so a bias b is taken out by
    // -b in the register's 32.8 counts per deg/s: 1.0 deg/s is -33, -0.5 is +16, 0.25 is -8.
    #[test]
    fn the_gyro_offset_lines_add_minus_the_bias_in_the_register_s_counts() {
        let text = String::from_utf8(i2cdevlib(&super::super::example_source()).bytes).unwrap();
        let text = text.lines().map(str::trim).collect::<Vec<_>>().join("\n");
        for line in [
            "mpu.setXGyroOffset(mpu.getXGyroOffset() + (-33));",
            "mpu.setYGyroOffset(mpu.getYGyroOffset() + (16));",
            "mpu.setZGyroOffset(mpu.getZGyroOffset() + (-8));",
        ] {
            assert!(text.lines().any(|l| l == line), "no `{line}` in\n{text}");
        }
    }

    /// The counts each accelerometer line adds.
    fn added_accel_counts(text: &str) -> Vec<i32> {
        ["X", "Y", "Z"]
            .iter()
            .map(|axis| {
                let key = format!("get{axis}AccelOffset() + (");
                let line = text.lines().find(|l| l.contains(&key)).expect("an accelerometer line");
                let tail = &line[line.find(&key).unwrap() + key.len()..];
                tail.split(')').next().unwrap().parse().unwrap()
            })
            .collect()
    }

    // NOTE: bit 0 of XA_OFFS_H/L (and Y, Z) is reserved (InvenSense, MPU Hardware Offset Registers
    // Application Note): an even count added keeps it, and stays within one count of the offset.
    #[test]
    fn the_accelerometer_lines_add_even_counts_within_one_count_of_the_offset() {
        let source = super::super::example_source();
        let text = String::from_utf8(i2cdevlib(&source).bytes).unwrap();
        let counts = added_accel_counts(&text);
        for (axis, count) in counts.iter().enumerate() {
            assert_eq!(count % 2, 0, "axis {axis} adds an odd {count}: bit 0 would change\n{text}");
            let wanted = -source.full().offset_g[axis] * ACCEL_OFFSET_LSB_PER_G;
            assert!((f64::from(*count) - wanted).abs() <= 1.0, "axis {axis}: {count} for {wanted:.2} counts");
        }
        assert!(text.contains("bit 0 of each accelerometer register is reserved"), "{text}");
    }

    #[test]
    fn the_statement_names_the_targets_that_carry_the_whole_calibration() {
        let text = String::from_utf8(i2cdevlib(&super::super::example_source()).bytes).unwrap();
        assert!(text.lines().any(|l| l.starts_with("// all of it: --to c carries M, o, G, b in full")), "{text}");
        assert!(text.contains("--to c-fixed on a part with no floating-point unit, such as an 8-bit AVR"), "{text}");
    }

    #[test]
    fn a_stream_from_i2cdevlib_s_raw_example_names_its_object_accelgyro_in_a_function() {
        let mut source = super::super::example_source();
        let text = String::from_utf8(i2cdevlib(&source).bytes).unwrap();
        assert!(text.contains("static inline void accelcal_add_offsets(MPU6050 &mpu) {"), "{text}");
        source.readings = Readings::stream(AccelUnit::Counts2g, Some("counts-250dps"), Some("i2cdevlib"));
        let text = String::from_utf8(i2cdevlib(&source).bytes).unwrap();
        assert!(text.contains("static inline void accelcal_add_offsets(MPU6050 &accelgyro) {"), "{text}");
        assert!(text.contains("    accelgyro.setXAccelOffset(accelgyro.getXAccelOffset() + ("), "{text}");
        assert!(!text.contains("mpu."), "{text}");
    }
}
