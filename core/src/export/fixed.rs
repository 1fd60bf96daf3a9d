//! The fixed-point C header for parts without a floating-point unit: M and G as Q14 int16, o and b as
//! int16 raw counts, int32 arithmetic; it states the largest difference from the float correction.

use shared::linalg::{Mat3, Vec3};

use super::loss::{loss, Carried};
use super::statement::{lines, Said};
use super::{text, Export, ExportError, Source, C_BLOCK};

/// Fraction bits of the matrices: 1.0 is 16384, so entries up to +-1.99994 fit an int16.
const Q: u32 = 14;
const ONE: f64 = (1 << Q) as f64;

const CONVENTION: &[&str] = &[
    "a = M (m - o) in raw counts: out[i] = (sum_j M_q14[i][j] (raw[j] - o_lsb[j]) + 2^13) >> 14",
    "column vectors: M_q14[i][j] is row i (output axis i), column j (input axis j); M = M_q14 / 16384",
    "o_lsb, b_lsb are the offset and gyro bias in raw counts; the result is in raw counts (divide by the LSB per g for g)",
    "gyro: the same with G_q14 and b_lsb, result in gyro counts (LSB per deg/s below)",
    "NOTE: >> of a negative int32 is an arithmetic shift on gcc, clang and avr-gcc (implementation-defined in C)",
];

/// One quantised pair (matrix, offset) and its worst difference from the float correction.
struct Quantised {
    matrix: [[i16; 3]; 3],
    offset: [i16; 3],
    /// Per output axis, the largest |fixed - float| over every int16 reading, in counts.
    step_lsb: Vec3<f64>,
}

/// The C header (int16 Q14).
pub fn c_fixed(source: &Source) -> Result<Export, ExportError> {
    if let Some(printed) = source.readings.printed.as_ref().filter(|_| !source.takes_counts()) {
        return Err(ExportError::FixedNeedsCounts { units: printed.units() });
    }
    let full = source.full();
    let accel = quantise(&full.matrix, &full.offset_g.map(|v| v * source.accel_per_g()))?;
    let gyro_lsb = source.gyro_per_dps();
    let gyro = quantise(&full.gyro_matrix, &source.gyro_bias_dps().map(|v| v * gyro_lsb))?;
    let loss = loss(&full, &carried(&accel, &gyro, source.accel_per_g(), gyro_lsb));
    let step = format!(
        "M, o, G, b rounded to Q14 and whole counts; over every int16 reading the result differs from the \
         float correction by at most {} counts per axis (accelerometer) and {} (gyro)",
        list(&accel.step_lsb),
        list(&gyro.step_lsb)
    );
    let title = "C (int16 fixed point, Q14)";
    let said = Said { title, convention: CONVENTION, carries: &step, temperature: "not applied", lossy: false };
    Ok(text(lines(source, &said, &loss), &C_BLOCK, &body(source, &accel, &gyro), loss))
}

/// What the quantised values apply, in accelcal's units.
fn carried(accel: &Quantised, gyro: &Quantised, lsb_per_g: f64, gyro_lsb_per_dps: f64) -> Carried {
    Carried {
        matrix: accel.matrix.map(|row| row.map(|v| f64::from(v) / ONE)),
        offset_g: accel.offset.map(|v| f64::from(v) / lsb_per_g),
        gyro_matrix: gyro.matrix.map(|row| row.map(|v| f64::from(v) / ONE)),
        gyro_bias_dps: Some(gyro.offset.map(|v| f64::from(v) / gyro_lsb_per_dps)),
    }
}

/// The header's C code.
fn body(source: &Source, accel: &Quantised, gyro: &Quantised) -> String {
    format!(
        "\n#ifndef ACCELCAL_CALIBRATION_Q14_H\n#define ACCELCAL_CALIBRATION_Q14_H\n\n#include <stdint.h>\n\n\
         #define ACCELCAL_ACCEL_LSB_PER_G {}\n#define ACCELCAL_GYRO_LSB_PER_DPS {:?}f\n\
         /* The largest |fixed - float| per axis over every int16 reading, in counts. */\n\
         static const float accelcal_accel_step_lsb[3] = {};\nstatic const float accelcal_gyro_step_lsb[3] = {};\n\n\
         static const int16_t accelcal_accel_matrix_q14[3][3] = {};\nstatic const int16_t accelcal_accel_offset_lsb[3] = {};\n\
         static const int16_t accelcal_gyro_matrix_q14[3][3] = {};\nstatic const int16_t accelcal_gyro_bias_lsb[3] = {};\n\n{FUNCTIONS}\
         \n#endif /* ACCELCAL_CALIBRATION_Q14_H */\n",
        source.accel_per_g(),
        source.gyro_per_dps() as f32,
        float_list(&accel.step_lsb),
        float_list(&gyro.step_lsb),
        int_matrix(&accel.matrix),
        int_vector(&accel.offset),
        int_matrix(&gyro.matrix),
        int_vector(&gyro.offset),
    )
}

const FUNCTIONS: &str = "/* out = (matrix (raw - offset) + 2^13) >> 14, in counts. */
static inline void accelcal_q14_correct(const int16_t matrix[3][3], const int16_t offset[3], const int16_t raw[3], int32_t out[3]) {
    int32_t d[3];
    for (int j = 0; j < 3; j++) d[j] = (int32_t)raw[j] - offset[j];
    for (int i = 0; i < 3; i++) {
        int32_t sum = (int32_t)matrix[i][0] * d[0] + (int32_t)matrix[i][1] * d[1] + (int32_t)matrix[i][2] * d[2];
        out[i] = (sum + ((int32_t)1 << 13)) >> 14;
    }
}

/* Calibrated acceleration in counts (ACCELCAL_ACCEL_LSB_PER_G per g). */
static inline void accelcal_accel_counts(const int16_t raw[3], int32_t out[3]) {
    accelcal_q14_correct(accelcal_accel_matrix_q14, accelcal_accel_offset_lsb, raw, out);
}

/* Calibrated rate in counts (ACCELCAL_GYRO_LSB_PER_DPS per deg/s). */
static inline void accelcal_gyro_counts(const int16_t raw[3], int32_t out[3]) {
    accelcal_q14_correct(accelcal_gyro_matrix_q14, accelcal_gyro_bias_lsb, raw, out);
}
";

/// `matrix` in Q14 and `offset_lsb` in whole counts, with the bound on the difference they make:
/// per axis 0.5 (the result's rounding) + sum_j |M_q - M| max|raw - o_q| + sum_j |M_ij| |o_q - o|.
fn quantise(matrix: &Mat3<f64>, offset_lsb: &Vec3<f64>) -> Result<Quantised, ExportError> {
    let offset = offset_lsb.map(|v| v.round().clamp(-32768.0, 32767.0) as i16);
    let q = matrix.map(|row| row.map(|v| (v * ONE).round()));
    if q.iter().flatten().any(|v| v.abs() > 32767.0) {
        return Err(ExportError::FixedPointOverflow { reason: "a matrix entry exceeds 2 in Q14".to_owned() });
    }
    let span = offset.map(|o| 32768.0 + f64::from(o).abs());
    let largest_sum = (0..3).map(|i| (0..3).map(|j| q[i][j].abs() * span[j]).sum::<f64>()).fold(0.0, f64::max);
    if largest_sum + ONE / 2.0 >= f64::from(i32::MAX) {
        return Err(ExportError::FixedPointOverflow { reason: format!("a row's sum reaches {largest_sum:.0}") });
    }
    let step_lsb = [0, 1, 2].map(|i| {
        let matrix_part: f64 = (0..3).map(|j| (q[i][j] / ONE - matrix[i][j]).abs() * span[j]).sum();
        let offset_part: f64 = (0..3).map(|j| matrix[i][j].abs() * (f64::from(offset[j]) - offset_lsb[j]).abs()).sum();
        0.5 + matrix_part + offset_part
    });
    Ok(Quantised { matrix: q.map(|row| row.map(|v| v as i16)), offset, step_lsb })
}

/// The bound rounded up to 1e-4 count, so that what is stated is never below it.
fn up(v: f64) -> f64 {
    (v * 1e4).ceil() / 1e4
}

fn list(v: &Vec3<f64>) -> String {
    format!("{:.4} {:.4} {:.4}", up(v[0]), up(v[1]), up(v[2]))
}

fn float_list(v: &Vec3<f64>) -> String {
    format!("{{{:.4}f, {:.4}f, {:.4}f}}", up(v[0]), up(v[1]), up(v[2]))
}

fn int_vector(v: &[i16; 3]) -> String {
    format!("{{{}, {}, {}}}", v[0], v[1], v[2])
}

fn int_matrix(m: &[[i16; 3]; 3]) -> String {
    format!("{{{}, {}, {}}}", int_vector(&m[0]), int_vector(&m[1]), int_vector(&m[2]))
}
