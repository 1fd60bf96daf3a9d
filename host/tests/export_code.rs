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
#[cfg_attr(not(has_gcc), ignore = "needs gcc (apt-get install gcc libc6-dev); CI=true runs it")]
fn c_header_compiled_by_gcc_equals_accelcal_on_1000_raw_readings_within_1e_6_g() {
    if !tool("gcc", "apt-get install gcc") {
        return;
    }
    let header = export("c", "calibration.h", &[]);
    let dir = header.parent().unwrap();
    std::fs::write(dir.join("c_main.c"), C_MAIN).unwrap();
    let binary = dir.join("c_main");
    run(Command::new("gcc").args(["-std=c99", "-Wall", "-Werror", "-O2", "-o"]).arg(&binary).arg(dir.join("c_main.c")));
    let readings = raw_readings(1000);
    let rows = numbers(&run_with_input(&mut Command::new(&binary), &readings_text(&readings)));
    assert_float_rows(&rows, &readings, "C header");
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
#[cfg_attr(not(has_gcc), ignore = "needs gcc (apt-get install gcc libc6-dev); CI=true runs it")]
fn fixed_point_header_compiled_by_gcc_is_within_its_stated_step_on_1000_raw_readings() {
    if !tool("gcc", "apt-get install gcc") {
        return;
    }
    let header = export("c-fixed", "calibration_q14.h", &[]);
    let dir = header.parent().unwrap();
    std::fs::write(dir.join("q14_main.c"), C_FIXED_MAIN).unwrap();
    let binary = dir.join("q14_main");
    run(Command::new("gcc")
        .args(["-std=c99", "-Wall", "-Werror", "-O2", "-o"])
        .arg(&binary)
        .arg(dir.join("q14_main.c")));
    let readings = raw_readings(1000);
    let mut rows = numbers(&run_with_input(&mut Command::new(&binary), &readings_text(&readings)));
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
    body = re.search(name + r"\s*=\s*\{([^;]*)\};", text).group(1)
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
