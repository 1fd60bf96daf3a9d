//! The float code targets: a C header and a Rust module, each with M, o, G, b and apply functions from
//! raw counts, carrying the whole calibration.

use shared::linalg::{Mat3, Vec3};
use shared::STANDARD_GRAVITY;

use super::loss::loss;
use super::statement::{lines, Said};
use super::{float, text, Export, Source, C_BLOCK, SLASHES};

/// What both float code targets state.
const CONVENTION: &[&str] = &[
    "a = M (m - o): subtract the offset o from the reading m (in g), then multiply by M (3x3)",
    "column vectors: M[i][j] is row i (the output axis i), column j (the input axis j)",
    "m = raw counts / ACCEL_LSB_PER_G (from a stream in its own units: m = value / ACCEL_PER_G); a in g (times the g below for m/s^2)",
    "gyro: w = G (w_raw - b), w_raw = raw counts / GYRO_LSB_PER_DPS (value / GYRO_PER_DPS), in deg/s",
];

/// How the functions read their input: what a stream printed in decimal takes floats and the
/// stream's own units per g and per deg/s; the names and types a counts header has are its default.
fn as_printed(source: &Source, code: &str, names: &[(&str, &str)]) -> String {
    if source.takes_counts() {
        return code.to_owned();
    }
    names.iter().fold(code.to_owned(), |code, (counts, printed)| code.replace(counts, printed))
}

/// What a C header's counts become for a stream's printed values.
const C_PRINTED: &[(&str, &str)] = &[
    ("LSB_PER_", "PER_"),
    ("const int16_t raw[3]", "const float raw[3]"),
    ("from raw accelerometer counts", "from the accelerometer's values as the sketch printed them"),
    ("from raw gyro counts", "from the gyro's values as the sketch printed them"),
];

/// What a Rust module's counts become for a stream's printed values.
const RUST_PRINTED: &[(&str, &str)] = &[
    ("LSB_PER_", "PER_"),
    ("raw: [i16; 3]", "raw: [f32; 3]"),
    ("Raw accelerometer counts per g.", "The stream's accelerometer values per g."),
    ("Raw gyro counts per deg/s.", "The stream's gyro values per deg/s."),
    ("from raw accelerometer counts", "from the accelerometer's values as the sketch printed them"),
    ("from raw gyro counts", "from the gyro's values as the sketch printed them"),
];

const TEMPERATURE: &str = "not applied (M, o, G, b are the ones at the temperature above)";

const C_SAID: Said = Said {
    title: "C (float)",
    convention: CONVENTION,
    carries: "M, o, G, b in full (float32)",
    temperature: TEMPERATURE,
    lossy: false,
};

/// The C header (float).
pub fn c(source: &Source) -> Export {
    let full = source.full();
    let loss = loss(&full, &full);
    let body = format!(
        "\n#ifndef ACCELCAL_CALIBRATION_H\n#define ACCELCAL_CALIBRATION_H\n\n#include <stdint.h>\n\n\
         #define ACCELCAL_ACCEL_LSB_PER_G {:?}f\n#define ACCELCAL_GYRO_LSB_PER_DPS {:?}f\n\
         #define ACCELCAL_STANDARD_GRAVITY {STANDARD_GRAVITY}f\n\n\
         static const float accelcal_accel_matrix[3][3] = {};\nstatic const float accelcal_accel_offset_g[3] = {};\n\
         static const float accelcal_gyro_matrix[3][3] = {};\nstatic const float accelcal_gyro_bias_dps[3] = {};\n\n{C_FUNCTIONS}\
         \n#endif /* ACCELCAL_CALIBRATION_H */\n",
        source.accel_per_g(),
        source.gyro_per_dps() as f32,
        c_matrix(&full.matrix),
        c_vector(&full.offset_g),
        c_matrix(&full.gyro_matrix),
        c_vector(&source.gyro_bias_dps()),
    );
    text(lines(source, &C_SAID, &loss), &C_BLOCK, &as_printed(source, &body, C_PRINTED), loss)
}

/// The C apply functions (ours; the formula stated above).
const C_FUNCTIONS: &str = "/* out = matrix (in - offset) */
static inline void accelcal_correct(const float matrix[3][3], const float offset[3], const float in[3], float out[3]) {
    float d[3];
    for (int j = 0; j < 3; j++) d[j] = in[j] - offset[j];
    for (int i = 0; i < 3; i++) out[i] = matrix[i][0] * d[0] + matrix[i][1] * d[1] + matrix[i][2] * d[2];
}

/* Calibrated acceleration in g from raw accelerometer counts. */
static inline void accelcal_accel_g(const int16_t raw[3], float out_g[3]) {
    float m[3];
    for (int j = 0; j < 3; j++) m[j] = (float)raw[j] / ACCELCAL_ACCEL_LSB_PER_G;
    accelcal_correct(accelcal_accel_matrix, accelcal_accel_offset_g, m, out_g);
}

/* Calibrated acceleration in m/s^2 (g times ACCELCAL_STANDARD_GRAVITY). */
static inline void accelcal_accel_ms2(const int16_t raw[3], float out_ms2[3]) {
    accelcal_accel_g(raw, out_ms2);
    for (int i = 0; i < 3; i++) out_ms2[i] *= ACCELCAL_STANDARD_GRAVITY;
}

/* Calibrated rate in deg/s from raw gyro counts. */
static inline void accelcal_gyro_dps(const int16_t raw[3], float out_dps[3]) {
    float w[3];
    for (int j = 0; j < 3; j++) w[j] = (float)raw[j] / ACCELCAL_GYRO_LSB_PER_DPS;
    accelcal_correct(accelcal_gyro_matrix, accelcal_gyro_bias_dps, w, out_dps);
}
";

const RUST_SAID: Said = Said {
    title: "Rust (no_std)",
    convention: CONVENTION,
    carries: "M, o, G, b in full (f32)",
    temperature: TEMPERATURE,
    lossy: false,
};

/// The Rust module (no_std: core only).
pub fn rust(source: &Source) -> Export {
    let full = source.full();
    let loss = loss(&full, &full);
    let body = format!(
        "\n/// Raw accelerometer counts per g.\npub const ACCEL_LSB_PER_G: f32 = {:?};\n\
         /// Raw gyro counts per deg/s.\npub const GYRO_LSB_PER_DPS: f32 = {:?};\n\
         /// m/s^2 per g.\npub const STANDARD_GRAVITY: f32 = {STANDARD_GRAVITY:?};\n\
         /// M, row i = output axis i.\npub const ACCEL_MATRIX: [[f32; 3]; 3] = {};\n\
         /// o, in g.\npub const ACCEL_OFFSET_G: [f32; 3] = {};\n\
         /// G, row i = output axis i.\npub const GYRO_MATRIX: [[f32; 3]; 3] = {};\n\
         /// b, in deg/s.\npub const GYRO_BIAS_DPS: [f32; 3] = {};\n{RUST_FUNCTIONS}",
        source.accel_per_g(),
        source.gyro_per_dps() as f32,
        rust_matrix(&full.matrix),
        rust_vector(&full.offset_g),
        rust_matrix(&full.gyro_matrix),
        rust_vector(&source.gyro_bias_dps()),
    );
    text(lines(source, &RUST_SAID, &loss), &SLASHES, &as_printed(source, &body, RUST_PRINTED), loss)
}

const RUST_FUNCTIONS: &str = "
/// matrix (reading - offset).
pub fn correct(matrix: &[[f32; 3]; 3], offset: &[f32; 3], reading: [f32; 3]) -> [f32; 3] {
    let d = [reading[0] - offset[0], reading[1] - offset[1], reading[2] - offset[2]];
    [0, 1, 2].map(|i| matrix[i][0] * d[0] + matrix[i][1] * d[1] + matrix[i][2] * d[2])
}

/// Calibrated acceleration in g from raw accelerometer counts.
pub fn accel_g(raw: [i16; 3]) -> [f32; 3] {
    correct(&ACCEL_MATRIX, &ACCEL_OFFSET_G, raw.map(|v| f32::from(v) / ACCEL_LSB_PER_G))
}

/// Calibrated acceleration in m/s^2 (g times STANDARD_GRAVITY).
pub fn accel_ms2(raw: [i16; 3]) -> [f32; 3] {
    accel_g(raw).map(|v| v * STANDARD_GRAVITY)
}

/// Calibrated rate in deg/s from raw gyro counts.
pub fn gyro_dps(raw: [i16; 3]) -> [f32; 3] {
    correct(&GYRO_MATRIX, &GYRO_BIAS_DPS, raw.map(|v| f32::from(v) / GYRO_LSB_PER_DPS))
}
";

/// `{a, b, c}` with f32 literals.
pub fn c_vector(v: &Vec3<f64>) -> String {
    format!("{{{}f, {}f, {}f}}", float(v[0]), float(v[1]), float(v[2]))
}

/// `{{..}, {..}, {..}}`, rows.
pub fn c_matrix(m: &Mat3<f64>) -> String {
    format!("{{{}, {}, {}}}", c_vector(&m[0]), c_vector(&m[1]), c_vector(&m[2]))
}

fn rust_vector(v: &Vec3<f64>) -> String {
    format!("[{}, {}, {}]", float(v[0]), float(v[1]), float(v[2]))
}

fn rust_matrix(m: &Mat3<f64>) -> String {
    format!("[{}, {}, {}]", rust_vector(&m[0]), rust_vector(&m[1]), rust_vector(&m[2]))
}
