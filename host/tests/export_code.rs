//! The full-matrix exports, compiled or loaded by the target's own toolchain and applied to 1000
//! random raw readings: equal to accelcal's correction (written out in the test from the JSON).

mod export_common;

use std::process::Command;

use export_common::*;

const ACCEL_LSB_PER_G: f64 = 16384.0;
const GYRO_LSB_PER_DPS: f64 = 32.8;
/// Float32 targets against the f64 correction: within 1e-6 g, and for the gyro 3e-4 deg/s (float32 keeps 6e-8
/// of the +-1000 deg/s range per operation).
const FLOAT_TOLERANCE_G: f64 = 1e-6;
const FLOAT_TOLERANCE_DPS: f64 = 3e-4;

/// accelcal's correction of one raw reading: a in g, a in m/s^2, w in deg/s.
fn ours(raw: &[i16; 3]) -> ([f64; 3], [f64; 3], [f64; 3]) {
    let sim = simulated();
    let a = correct(&sim.matrix, &sim.offset, raw.map(|v| f64::from(v) / ACCEL_LSB_PER_G));
    let w = correct(&sim.gyro_matrix, &sim.gyro_bias, raw.map(|v| f64::from(v) / GYRO_LSB_PER_DPS));
    (a, a.map(|v| v * G), w)
}

/// Asserts each row's nine numbers equal ours within the tolerances.
fn assert_float_rows(rows: &[Vec<f64>], readings: &[[i16; 3]], what: &str) {
    assert_eq!(rows.len(), readings.len(), "{what}: one row per reading");
    let mut worst = [0.0f64; 3];
    for (row, raw) in rows.iter().zip(readings) {
        let (g, ms2, dps) = ours(raw);
        for i in 0..3 {
            worst[0] = worst[0].max((row[i] - g[i]).abs());
            worst[1] = worst[1].max((row[3 + i] - ms2[i]).abs());
            worst[2] = worst[2].max((row[6 + i] - dps[i]).abs());
        }
    }
    assert!(worst[0] <= FLOAT_TOLERANCE_G, "{what}: accel differs by {:.3e} g", worst[0]);
    assert!(worst[1] <= FLOAT_TOLERANCE_G * G, "{what}: accel in m/s^2 differs by {:.3e} m/s^2", worst[1]);
    assert!(worst[2] <= FLOAT_TOLERANCE_DPS, "{what}: gyro differs by {:.3e} deg/s", worst[2]);
}

/// gcc's flags for every C file the exports write: C99, every warning an error.
const C_FLAGS: &[&str] = &["-std=c99", "-Wall", "-Wextra", "-Werror", "-O2"];
/// g++'s flags for the same files compiled as C++ (a sketch's .ino is C++).
const CXX_FLAGS: &[&str] = &["-std=c++11", "-Wall", "-Wextra", "-Werror", "-O2"];

/// Compiles `source` (a main that includes an exported file in `dir`) as C with gcc and as C++ with
/// g++, under [`C_FLAGS`] and [`CXX_FLAGS`]; the two programs.
fn compile_as_c_and_cpp(dir: &std::path::Path, stem: &str, source: &str) -> [std::path::PathBuf; 2] {
    [("gcc", "c", C_FLAGS), ("g++", "cpp", CXX_FLAGS)].map(|(compiler, extension, flags)| {
        let file = dir.join(format!("{stem}.{extension}"));
        std::fs::write(&file, source).unwrap();
        let binary = dir.join(format!("{stem}_{extension}"));
        run(Command::new(compiler).args(flags).arg("-o").arg(&binary).arg(&file));
        binary
    })
}

/// Whether gcc and g++ are both there (else a skip, or under CI=true a failure).
fn compilers() -> bool {
    tool("gcc", "apt-get install gcc libc6-dev") && tool("g++", "apt-get install g++")
}

const C_MAIN: &str = r#"#include <stdio.h>
#include "calibration.h"
int main(void) {
    int16_t raw[3]; int x, y, z; float g[3], ms2[3], dps[3];
    while (scanf("%d %d %d", &x, &y, &z) == 3) {
        raw[0] = (int16_t)x; raw[1] = (int16_t)y; raw[2] = (int16_t)z;
        accelcal_accel_g(raw, g); accelcal_accel_ms2(raw, ms2); accelcal_gyro_dps(raw, dps);
        printf("%.9e %.9e %.9e %.9e %.9e %.9e %.9e %.9e %.9e\n", g[0], g[1], g[2], ms2[0], ms2[1], ms2[2], dps[0], dps[1], dps[2]);
    }
    return 0;
}
"#;

#[test]
#[cfg_attr(
    not(all(has_gcc, has_gxx)),
    ignore = "needs gcc and g++ (apt-get install gcc g++ libc6-dev); CI=true runs it"
)]
fn c_header_compiled_as_c_and_cpp_equals_accelcal_on_1000_raw_readings_within_1e_6_g() {
    if !compilers() {
        return;
    }
    let header = export("c", "calibration.h", &[]);
    let readings = raw_readings(1000);
    for binary in compile_as_c_and_cpp(header.parent().unwrap(), "c_main", C_MAIN) {
        let rows = numbers(&run_with_input(&mut Command::new(&binary), &readings_text(&readings)));
        assert_float_rows(&rows, &readings, &format!("C header ({binary:?})"));
    }
}

const C_FIXED_MAIN: &str = r#"#include <stdio.h>
#include "calibration_q14.h"
int main(void) {
    int16_t raw[3]; int x, y, z; int32_t a[3], w[3];
    while (scanf("%d %d %d", &x, &y, &z) == 3) {
        raw[0] = (int16_t)x; raw[1] = (int16_t)y; raw[2] = (int16_t)z;
        accelcal_accel_counts(raw, a); accelcal_gyro_counts(raw, w);
        printf("%ld %ld %ld %ld %ld %ld\n", (long)a[0], (long)a[1], (long)a[2], (long)w[0], (long)w[1], (long)w[2]);
    }
    printf("%.6f %.6f %.6f %.6f %.6f %.6f\n", accelcal_accel_step_lsb[0], accelcal_accel_step_lsb[1], accelcal_accel_step_lsb[2],
           accelcal_gyro_step_lsb[0], accelcal_gyro_step_lsb[1], accelcal_gyro_step_lsb[2]);
    return 0;
}
"#;

#[test]
#[cfg_attr(
    not(all(has_gcc, has_gxx)),
    ignore = "needs gcc and g++ (apt-get install gcc g++ libc6-dev); CI=true runs it"
)]
fn fixed_point_header_compiled_as_c_and_cpp_is_within_its_stated_step_on_1000_raw_readings() {
    if !compilers() {
        return;
    }
    let header = export("c-fixed", "calibration_q14.h", &[]);
    for binary in compile_as_c_and_cpp(header.parent().unwrap(), "q14_main", C_FIXED_MAIN) {
        assert_within_the_stated_step(&binary);
    }
}

/// Runs the fixed-point program on 1000 raw readings: each result within the step it states.
fn assert_within_the_stated_step(binary: &std::path::Path) {
    let readings = raw_readings(1000);
    let mut rows = numbers(&run_with_input(&mut Command::new(binary), &readings_text(&readings)));
    let step = rows.pop().unwrap();
    assert!(step[..3].iter().all(|s| *s > 0.0 && *s < 8.0), "stated accel step {step:?} counts is not a few counts");
    for (row, raw) in rows.iter().zip(&readings) {
        let (g, _, dps) = ours(raw);
        for i in 0..3 {
            let accel_error = (row[i] - g[i] * ACCEL_LSB_PER_G).abs();
            let gyro_error = (row[3 + i] - dps[i] * GYRO_LSB_PER_DPS).abs();
            assert!(
                accel_error <= step[i],
                "reading {raw:?} axis {i}: {accel_error:.3} counts off, stated step {}",
                step[i]
            );
            assert!(
                gyro_error <= step[3 + i],
                "reading {raw:?} gyro axis {i}: {gyro_error:.3} counts off, stated {}",
                step[3 + i]
            );
        }
    }
}

const RUST_MAIN: &str = r#"mod calibration;
use std::io::BufRead;
fn main() {
    for line in std::io::stdin().lock().lines() {
        let v: Vec<i16> = line.unwrap().split_whitespace().map(|x| x.parse().unwrap()).collect();
        let raw = [v[0], v[1], v[2]];
        let (g, ms2, dps) = (calibration::accel_g(raw), calibration::accel_ms2(raw), calibration::gyro_dps(raw));
        println!("{:e} {:e} {:e} {:e} {:e} {:e} {:e} {:e} {:e}", g[0], g[1], g[2], ms2[0], ms2[1], ms2[2], dps[0], dps[1], dps[2]);
    }
}
"#;

#[test]
fn rust_module_builds_no_std_and_equals_accelcal_on_1000_raw_readings_within_1e_6_g() {
    let module = export("rust", "calibration.rs", &[]);
    let dir = module.parent().unwrap();
    // no_std: the module alone as a #![no_std] library.
    std::fs::write(dir.join("nostd.rs"), "#![no_std]\npub mod calibration;\n").unwrap();
    let rustc = std::env::var("RUSTC").unwrap_or_else(|_| "rustc".to_owned());
    run(Command::new(&rustc)
        .args(["--edition", "2021", "--crate-type", "rlib", "-D", "warnings", "--out-dir"])
        .arg(dir)
        .arg(dir.join("nostd.rs")));
    std::fs::write(dir.join("rust_main.rs"), RUST_MAIN).unwrap();
    let binary = dir.join("rust_main");
    run(Command::new(&rustc).args(["--edition", "2021", "-O", "-o"]).arg(&binary).arg(dir.join("rust_main.rs")));
    let readings = raw_readings(1000);
    let rows = numbers(&run_with_input(&mut Command::new(&binary), &readings_text(&readings)));
    assert_float_rows(&rows, &readings, "Rust module");
}

/// Reads the Fusion values from the exported file (row-major, as FusionMatrix stores them) and applies
/// imufusion's model_inertial, Fusion's own calibration model, to every reading.
const FUSION_PY: &str = r#"
import re, sys, numpy as np, imufusion
text = open(sys.argv[1]).read()
def values(name):
    body = re.search(name + r"\s*=\s*\{([^;]*)\};", text).group(1).replace("{", "").replace("}", "")
    return np.array([float(v.strip().rstrip("f")) for v in body.split(",")])
acc = [values("accelerometerMisalignment").reshape(3, 3), values("accelerometerSensitivity"), values("accelerometerOffset")]
gyr = [values("gyroscopeMisalignment").reshape(3, 3), values("gyroscopeSensitivity"), values("gyroscopeOffset")]
for line in sys.stdin:
    raw = np.array([float(v) for v in line.split()])
    a = imufusion.model_inertial(raw, *acc)
    w = imufusion.model_inertial(raw, *gyr)
    print(" ".join("%.9e" % v for v in list(a) + list(a * 9.80665) + list(w)))
"#;

#[test]
#[cfg_attr(not(has_imufusion), ignore = "needs imufusion (pip install imufusion); CI=true runs it")]
fn fusion_values_loaded_by_imufusion_equal_accelcal_on_1000_raw_readings_within_1e_6_g() {
    let found = Command::new("python3").args(["-c", "import imufusion, numpy"]).status().is_ok_and(|s| s.success());
    if !found {
        assert!(
            std::env::var("CI").as_deref() != Ok("true"),
            "CI=true but imufusion is missing (pip install imufusion)"
        );
        eprintln!(
            "SKIPPED: python3 with imufusion is not installed (pip install imufusion); CI=true makes this a failure"
        );
        return;
    }
    let file = export("fusion", "fusion_calibration.h", &[]);
    let script = file.parent().unwrap().join("fusion.py");
    std::fs::write(&script, FUSION_PY).unwrap();
    let readings = raw_readings(1000);
    let rows = numbers(&run_with_input(Command::new("python3").arg(&script).arg(&file), &readings_text(&readings)));
    assert_float_rows(&rows, &readings, "Fusion (imufusion)");
}

#[test]
#[cfg_attr(not(has_octave), ignore = "needs Octave (apt-get install --no-install-recommends octave); CI=true runs it")]
fn matlab_script_run_by_octave_equals_accelcal_on_1000_raw_readings_within_1e_6_g() {
    if !tool("octave", "apt-get install --no-install-recommends octave") {
        return;
    }
    let script = export("matlab", "accelcal_calibration.m", &[]);
    let dir = script.parent().unwrap();
    let readings = raw_readings(1000);
    let input = dir.join("raw.txt");
    std::fs::write(&input, readings_text(&readings)).unwrap();
    let program = format!(
        "source('{}'); R = dlmread('{}'); C = (R / accel_lsb_per_g - b) * A; W = (R / gyro_lsb_per_dps - bg) * Ag; \
         printf('%.9e %.9e %.9e %.9e %.9e %.9e %.9e %.9e %.9e\\n', [C, C * standard_gravity, W]');",
        script.display(),
        input.display()
    );
    let rows =
        numbers(&run(Command::new("octave").args(["--no-gui", "--quiet", "--no-init-file", "--eval", &program])));
    assert_float_rows(&rows, &readings, "MATLAB script (Octave)");
}

/// The part of `accelcal noise --json` the kalibr export reads (Kalibr's continuous-time densities).
const KALIBR_NOISE_JSON: &str = r#"{"sample_rate_hz": 1000.0, "kalibr": {"continuous_time": {
 "accelerometer_noise_density": 1.5e-3, "accelerometer_random_walk": 2e-4,
 "gyroscope_noise_density": 8e-5, "gyroscope_random_walk": 3e-6}}}"#;

#[test]
#[cfg_attr(not(has_pyyaml), ignore = "needs PyYAML (pip install pyyaml); CI=true runs it")]
fn kalibr_imu_yaml_is_read_by_a_yaml_parser_with_the_noise_terms_and_rate() {
    let noise = simulated().dir.join("kalibr_noise.json");
    std::fs::write(&noise, KALIBR_NOISE_JSON).unwrap();
    let file = export("kalibr", "kalibr_imu.yaml", &["--noise", noise.to_str().unwrap()]);
    let keys = "accelerometer_noise_density accelerometer_random_walk gyroscope_noise_density \
                gyroscope_random_walk update_rate";
    let script = "import sys, yaml\nd = yaml.safe_load(open(sys.argv[1]))\n\
                  print(' '.join(repr(float(d[k])) for k in sys.argv[2].split()))";
    let text = run(Command::new("python3").args(["-c", script]).arg(&file).arg(keys));
    assert_eq!(numbers(&text), vec![vec![1.5e-3, 2e-4, 8e-5, 3e-6, 1000.0]], "{file:?}");
}

/// The two types of Fusion's FusionMath.h the export names, as Fusion declares them (unions whose first
/// member is the float array), so that the file compiles here without Fusion itself.
const FUSION_TYPES_H: &str = r#"#ifndef FUSION_H
#define FUSION_H
typedef union { float array[3]; struct { float x; float y; float z; } axis; } FusionVector;
typedef union { float array[9]; struct { float xx, xy, xz, yx, yy, yz, zx, zy, zz; } element; } FusionMatrix;
#endif
"#;

/// Applies Fusion's inertial model, misalignment * ((uncalibrated - offset) .* sensitivity), to raw counts.
const FUSION_MAIN: &str = r#"#include <stdio.h>
#include "fusion_compiled.h"
static void model(const FusionMatrix *m, const FusionVector *s, const FusionVector *o, const float raw[3], float out[3]) {
    float d[3];
    for (int j = 0; j < 3; j++) d[j] = (raw[j] - o->array[j]) * s->array[j];
    for (int i = 0; i < 3; i++) out[i] = m->array[3 * i] * d[0] + m->array[3 * i + 1] * d[1] + m->array[3 * i + 2] * d[2];
}
int main(void) {
    int x, y, z; float raw[3], a[3], w[3];
    while (scanf("%d %d %d", &x, &y, &z) == 3) {
        raw[0] = (float)x; raw[1] = (float)y; raw[2] = (float)z;
        model(&accelerometerMisalignment, &accelerometerSensitivity, &accelerometerOffset, raw, a);
        model(&gyroscopeMisalignment, &gyroscopeSensitivity, &gyroscopeOffset, raw, w);
        printf("%.9e %.9e %.9e %.9e %.9e %.9e %.9e %.9e %.9e\n", a[0], a[1], a[2], a[0] * 9.80665f, a[1] * 9.80665f,
               a[2] * 9.80665f, w[0], w[1], w[2]);
    }
    return 0;
}
"#;

#[test]
#[cfg_attr(
    not(all(has_gcc, has_gxx)),
    ignore = "needs gcc and g++ (apt-get install gcc g++ libc6-dev); CI=true runs it"
)]
fn fusion_file_compiled_as_c_and_cpp_against_fusion_s_types_equals_accelcal_within_1e_6_g() {
    if !compilers() {
        return;
    }
    let file = export("fusion", "fusion_compiled.h", &[]);
    let dir = file.parent().unwrap();
    std::fs::write(dir.join("Fusion.h"), FUSION_TYPES_H).unwrap();
    let readings = raw_readings(1000);
    for binary in compile_as_c_and_cpp(dir, "fusion_main", FUSION_MAIN) {
        let rows = numbers(&run_with_input(&mut Command::new(&binary), &readings_text(&readings)));
        assert_float_rows(&rows, &readings, &format!("Fusion values ({binary:?})"));
    }
}

/// i2cdevlib's MPU6050 offset accessors (MPU6050.h) over six registers: the accelerometer's start at
/// factory trims with bit 0 set on two axes, as a chip's may be.
const MPU6050_STUB_H: &str = r#"#pragma once
#include <stdint.h>
class MPU6050 {
public:
    int16_t reg[6] = {-2693, 594, 1687, 10, -20, 30};
    int16_t getXAccelOffset() { return reg[0]; } void setXAccelOffset(int16_t v) { reg[0] = v; }
    int16_t getYAccelOffset() { return reg[1]; } void setYAccelOffset(int16_t v) { reg[1] = v; }
    int16_t getZAccelOffset() { return reg[2]; } void setZAccelOffset(int16_t v) { reg[2] = v; }
    int16_t getXGyroOffset() { return reg[3]; } void setXGyroOffset(int16_t v) { reg[3] = v; }
    int16_t getYGyroOffset() { return reg[4]; } void setYGyroOffset(int16_t v) { reg[4] = v; }
    int16_t getZGyroOffset() { return reg[5]; } void setZGyroOffset(int16_t v) { reg[5] = v; }
};
"#;

/// A sketch that includes the export at file scope and calls it on its object.
const I2CDEVLIB_MAIN: &str = r#"#include <stdio.h>
#include "MPU6050.h"
#include "accelcal_offsets.h"
MPU6050 mpu;
int main() {
    accelcal_add_offsets(mpu);
    printf("%d %d %d %d %d %d\n", mpu.reg[0], mpu.reg[1], mpu.reg[2], mpu.reg[3], mpu.reg[4], mpu.reg[5]);
    return 0;
}
"#;

#[test]
#[cfg_attr(not(has_gxx), ignore = "needs g++ (apt-get install g++); CI=true runs it")]
fn i2cdevlib_header_compiled_by_gxx_keeps_bit_0_and_takes_out_the_offsets_to_a_register_step() {
    if !tool("g++", "apt-get install g++") {
        return;
    }
    let sim = simulated();
    let header = export("i2cdevlib", "accelcal_offsets.h", &[]);
    let dir = header.parent().unwrap();
    std::fs::write(dir.join("MPU6050.h"), MPU6050_STUB_H).unwrap();
    std::fs::write(dir.join("i2cdevlib_main.cpp"), I2CDEVLIB_MAIN).unwrap();
    let binary = dir.join("i2cdevlib_main");
    run(Command::new("g++").args(CXX_FLAGS).arg("-o").arg(&binary).arg(dir.join("i2cdevlib_main.cpp")));
    let after = numbers(&run(&mut Command::new(&binary)))[0].clone();
    let before = [-2693.0, 594.0, 1687.0, 10.0, -20.0, 30.0];
    for axis in 0..3 {
        assert_eq!((after[axis] as i64) & 1, (before[axis] as i64) & 1, "axis {axis}: bit 0 changed, {after:?}");
        // NOTE: the register adds to the reading, 2048 counts per g: it takes out the offset to one
        // register step of 2 counts (half a step each way), and the gyro's to half a count at 32.8 per deg/s.
        let added_g = (after[axis] - before[axis]) / 2048.0;
        assert!((added_g + sim.offset[axis]).abs() * 2048.0 <= 1.0 + 1e-9, "axis {axis}: {added_g} g added");
        let added_dps = (after[3 + axis] - before[3 + axis]) / 32.8;
        assert!((added_dps + sim.gyro_bias[axis]).abs() * 32.8 <= 0.5 + 1e-9, "gyro axis {axis}: {added_dps}");
    }
}

/// A sketch printing m/s^2 and rad/s (Adafruit_MPU6050's examples): six decimal values a line.
const PRINTED_MAIN: &str = r#"#include <stdio.h>
#include "printed_calibration.h"
int main(void) {
    float a[3], w[3], g[3], ms2[3], dps[3];
    while (scanf("%f %f %f %f %f %f", &a[0], &a[1], &a[2], &w[0], &w[1], &w[2]) == 6) {
        accelcal_accel_g(a, g); accelcal_accel_ms2(a, ms2); accelcal_gyro_dps(w, dps);
        printf("%.9e %.9e %.9e %.9e %.9e %.9e %.9e %.9e %.9e\n", g[0], g[1], g[2], ms2[0], ms2[1], ms2[2], dps[0], dps[1], dps[2]);
    }
    return 0;
}
"#;

/// A session file of a stream in m/s^2 and rad/s with the simulated calibration's captures (a stream
/// session keeps its captures in g, as every session does).
fn stream_session_in_m_s2() -> std::path::PathBuf {
    let dir = simulated().dir.join("printed");
    std::fs::create_dir_all(&dir).unwrap();
    let stem = dir.join("board");
    let output =
        accelcal(&["calibrate", "--sim", "--sim-sensor", "settled", "--yes", "--session", stem.to_str().unwrap()]);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let mut session: serde_json::Value = serde_json::from_str(&read(&dir.join("board.json"))).unwrap();
    let object = session.as_object_mut().unwrap();
    object.remove("board");
    object.insert("kind".into(), "stream".into());
    let stream = r#"{"port": "/dev/ttyUSB0", "log": "s.log", "dialect": "adafruit-plotter", "input_unit": "m/s2",
                     "gyro_unit": "rad/s", "rate_hz": 100.0}"#;
    object.insert("stream".into(), serde_json::from_str(stream).unwrap());
    let path = dir.join("stream.json");
    std::fs::write(&path, serde_json::to_string(&session).unwrap()).unwrap();
    path
}

#[test]
#[cfg_attr(
    not(all(has_gcc, has_gxx)),
    ignore = "needs gcc and g++ (apt-get install gcc g++ libc6-dev); CI=true runs it"
)]
fn c_header_of_a_stream_in_m_s2_fed_the_printed_values_gives_the_calibrated_g_within_1e_6() {
    if !compilers() {
        return;
    }
    let session = stream_session_in_m_s2();
    let dir = session.parent().unwrap();
    let header = dir.join("printed_calibration.h");
    let output = accelcal(&["export", session.to_str().unwrap(), "--to", "c", "-o", header.to_str().unwrap()]);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let text = read(&header);
    assert!(text.contains("accelerometer in m/s2 (9.80665 per g), gyro in rad/s"), "{text}");
    // What the sketch prints of each raw reading: m/s^2 and rad/s, to 4 decimals.
    let printed: Vec<[f64; 6]> = raw_readings(1000)
        .iter()
        .map(|r| {
            let a = r.map(|v| f64::from(v) / ACCEL_LSB_PER_G * G);
            let w = r.map(|v| (f64::from(v) / GYRO_LSB_PER_DPS).to_radians());
            [a[0], a[1], a[2], w[0], w[1], w[2]].map(|v| (v * 1e4).round() / 1e4)
        })
        .collect();
    let input: String =
        printed.iter().map(|p| format!("{} {} {} {} {} {}\n", p[0], p[1], p[2], p[3], p[4], p[5])).collect();
    // The session's calibration is the simulated run's: the same settled sensor and seed.
    let sim = simulated();
    for binary in compile_as_c_and_cpp(dir, "printed_main", PRINTED_MAIN) {
        let rows = numbers(&run_with_input(&mut Command::new(&binary), &input));
        let mut worst = [0.0f64; 2];
        for (row, p) in rows.iter().zip(&printed) {
            let g = correct(&sim.matrix, &sim.offset, [p[0], p[1], p[2]].map(|v| v / G));
            let dps = correct(&sim.gyro_matrix, &sim.gyro_bias, [p[3], p[4], p[5]].map(f64::to_degrees));
            for i in 0..3 {
                worst[0] = worst[0].max((row[i] - g[i]).abs());
                worst[1] = worst[1].max((row[6 + i] - dps[i]).abs());
            }
        }
        assert!(worst[0] <= FLOAT_TOLERANCE_G, "{binary:?}: {:.3e} g from the calibrated g", worst[0]);
        assert!(worst[1] <= FLOAT_TOLERANCE_DPS, "{binary:?}: {:.3e} deg/s from the calibrated rate", worst[1]);
    }
}

/// A complete minimal ESPHome node (an ESP32 board, its I2C bus) that includes the export as a package.
const ESPHOME_NODE: &str = "esphome:\n  name: accelcal-check\nesp32:\n  board: esp32dev\ni2c:\n  sda: 21\n  scl: 22\n\
                            packages:\n  accelcal: !include accelcal_esphome.yaml\n";

#[test]
#[cfg_attr(not(has_esphome), ignore = "needs ESPHome (pip install esphome); CI=true runs it")]
fn esphome_config_accepts_a_node_that_includes_the_export() {
    let found = Command::new("python3").args(["-m", "esphome", "version"]).output().is_ok_and(|o| o.status.success());
    if !found {
        assert!(std::env::var("CI").as_deref() != Ok("true"), "CI=true but ESPHome is missing (pip install esphome)");
        eprintln!("SKIPPED: ESPHome is not installed (pip install esphome); CI=true makes this a failure");
        return;
    }
    std::fs::create_dir_all(simulated().dir.join("esphome")).unwrap();
    let fragment = export("esphome", "esphome/accelcal_esphome.yaml", &[]);
    let node = fragment.parent().unwrap().join("node.yaml");
    std::fs::write(&node, ESPHOME_NODE).unwrap();
    let said = run(Command::new("python3").args(["-m", "esphome", "config"]).arg(&node));
    // NOTE: `esphome config` prints the validated configuration: the filters and lambdas are in it.
    assert!(said.contains("multiply:") && said.contains("id(accelcal_accel_z).state"), "{said}");
}

/// ESPHome's mpu6050 as its mpu6050.cpp publishes (m/s^2 = raw * 0.000061 * 9.80665, deg/s = raw *
/// 0.060975), then the export's filters (multiply, offset, in order) on each axis and the template
/// sensors' lambdas (C++ arithmetic on floats, evaluated here); per line: templates' accel, gyro, then the
/// filtered accel.
const ESPHOME_PY: &str = r#"
import re, sys, yaml
sensors = yaml.safe_load(open(sys.argv[1]))["sensor"]
platform = next(s for s in sensors if s["platform"] == "mpu6050")
templates = {s["id"]: s["lambda"] for s in sensors if s["platform"] == "template"}
def filtered(value, filters):
    for f in filters:
        (name, number), = f.items()
        value = value * number if name == "multiply" else value + number if name == "offset" else None
    return value
def evaluate(source, states):
    body = re.fullmatch(r"\s*return (.*);\s*", source).group(1)
    body = re.sub(r"id\((\w+)\)\.state", r"states['\1']", re.sub(r"(\d)f\b", r"\1", body))
    return eval(body, {"states": states})
axes = [k + "_" + a for k in ("accel", "gyro") for a in "xyz"]
for line in sys.stdin:
    raw = [float(v) for v in line.split()]
    published = [r * 0.000061 * 9.80665 for r in raw[:3]] + [r * 0.060975 for r in raw[3:]]
    states = {platform[k]["id"]: filtered(v, platform[k]["filters"]) for k, v in zip(axes, published)}
    out = [evaluate(templates["accelcal_" + k + "_calibrated"], states) for k in axes]
    print(" ".join("%.12e" % v for v in out + [states["accelcal_" + k] for k in axes[:3]]))
"#;

/// The counts ESPHome reads (+-2 g, +-2000 deg/s: 16384 per g, 16.4 per deg/s) where the calibrated
/// sensor feels `u` (in g) and turns at 500 deg/s about `u`.
fn esphome_raw(u: [f64; 3]) -> [f64; 6] {
    let sim = simulated();
    let m = correct(&inverse(&sim.matrix), &[0.0; 3], u);
    let w = correct(&inverse(&sim.gyro_matrix), &[0.0; 3], u.map(|v| 500.0 * v));
    let a = [0, 1, 2].map(|i| (m[i] + sim.offset[i]) * 16384.0);
    let w = [0, 1, 2].map(|i| (w[i] + sim.gyro_bias[i]) * 16.4);
    [a[0], a[1], a[2], w[0], w[1], w[2]]
}

#[test]
#[cfg_attr(not(has_pyyaml), ignore = "needs PyYAML (pip install pyyaml); CI=true runs it")]
fn esphome_templates_give_accelcal_s_correction_and_its_filters_alone_lose_what_the_file_states() {
    let fragment = export("esphome", "accelcal_esphome.yaml", &[]);
    let script = fragment.parent().unwrap().join("esphome.py");
    std::fs::write(&script, ESPHOME_PY).unwrap();
    let directions = directions(2000);
    let input: String =
        directions.iter().map(|u| esphome_raw(*u).map(|v| format!("{v:.6} ")).concat() + "\n").collect();
    let rows = numbers(&run_with_input(Command::new("python3").arg(&script).arg(&fragment), &input));
    let (mut worst, mut per_axis) = ([0.0f64; 2], Vec::new());
    for (row, u) in rows.iter().zip(&directions) {
        for i in 0..3 {
            worst[0] = worst[0].max((row[i] / G - u[i]).abs());
            worst[1] = worst[1].max((row[3 + i] - 500.0 * u[i]).abs());
        }
        per_axis.push((0..3).map(|i| (row[6 + i] / G - u[i]).powi(2)).sum::<f64>().sqrt());
    }
    assert!(worst[0] <= FLOAT_TOLERANCE_G, "templates: {:.3e} g from accelcal's correction", worst[0]);
    assert!(worst[1] <= FLOAT_TOLERANCE_DPS, "templates: {:.3e} deg/s from accelcal's correction", worst[1]);
    let rms_mg = (per_axis.iter().map(|e| e * e).sum::<f64>() / per_axis.len() as f64).sqrt() * 1e3;
    let text = read(&fragment);
    let line = text.lines().find(|l| l.contains("per-axis sensors alone (filters")).expect("a per-axis loss line");
    let stated: f64 = line.split("): ").nth(1).unwrap().split(' ').next().unwrap().parse().unwrap();
    assert!((stated - rms_mg).abs() <= 0.1 * rms_mg, "per-axis: stated {stated} mg rms, measured {rms_mg:.4}");
}
