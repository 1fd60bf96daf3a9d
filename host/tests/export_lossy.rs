//! The exports that cannot carry the whole calibration: each file is read back here as its target
//! reads it, applied to the simulated sensor's true errors, and the loss measured so must match the
//! loss the file states (within 10 %). The EEPROM image is read as Adafruit_Sensor_Calibration reads it.

mod export_common;

use export_common::*;

/// What a target applies, read back from its file: a = scale .* (m - offset), w = w_raw - gyro_bias.
struct Applied {
    scale: [f64; 3],
    offset_g: [f64; 3],
    gyro_bias_dps: Option<[f64; 3]>,
}

const RAD_PER_DEG: f64 = std::f64::consts::PI / 180.0;

/// `NAME,VALUE` or tab-separated QGroundControl lines: the value of `name`.
fn param(text: &str, name: &str) -> f64 {
    text.lines()
        .filter(|l| !l.starts_with('#'))
        .find_map(|l| {
            let fields: Vec<&str> = l.split([',', '\t']).collect();
            let at = fields.iter().position(|f| *f == name)?;
            fields.get(at + 1)?.trim().parse().ok()
        })
        .unwrap_or_else(|| panic!("no parameter {name}"))
}

fn autopilot(text: &str, offset: &str, scale: &str, gyro: &str) -> Applied {
    let name = |pattern: &str, axis: &str| pattern.replace('#', axis);
    let per_axis = |pattern: &str| ["X", "Y", "Z"].map(|a| param(text, &name(pattern, a)));
    Applied {
        scale: per_axis(scale),
        offset_g: per_axis(offset).map(|v| v / G),
        gyro_bias_dps: Some(per_axis(gyro).map(|v| v / RAD_PER_DEG)),
    }
}

/// The integers after `prefix` on the line that has it.
fn integers(text: &str, prefix: &str) -> Vec<f64> {
    let line = text.lines().find(|l| l.contains(prefix)).unwrap_or_else(|| panic!("no {prefix:?}"));
    let tail = &line[line.find(prefix).unwrap() + prefix.len()..];
    tail.split(|c: char| !(c.is_ascii_digit() || c == '-'))
        .filter(|s| !s.is_empty() && *s != "-")
        .map(|s| s.parse().unwrap())
        .collect()
}

fn read_back(target: &str, text: &str) -> Applied {
    match target {
        "ardupilot" => autopilot(text, "INS_ACCOFFS_#", "INS_ACCSCAL_#", "INS_GYROFFS_#"),
        "px4" => autopilot(text, "CAL_ACC0_#OFF", "CAL_ACC0_#SCALE", "CAL_GYRO0_#OFF"),
        "betaflight" => {
            let v = integers(text, "set acc_calibration =");
            Applied { scale: [1.0; 3], offset_g: [v[0], v[1], v[2]].map(|c| c / 2048.0), gyro_bias_dps: None }
        }
        "inav" => {
            let zero = ["x", "y", "z"].map(|a| integers(text, &format!("set acczero_{a} ="))[0] / 4096.0);
            let gain = ["x", "y", "z"].map(|a| integers(text, &format!("set accgain_{a} ="))[0] / 4096.0);
            Applied { scale: gain, offset_g: zero, gyro_bias_dps: None }
        }
        "i2cdevlib" => {
            let accel = ["X", "Y", "Z"].map(|a| integers(text, &format!("get{a}AccelOffset() +"))[0]);
            let gyro = ["X", "Y", "Z"].map(|a| integers(text, &format!("get{a}GyroOffset() +"))[0]);
            // NOTE: the registers add to the reading: 2048 counts per g, 32.8 per deg/s.
            Applied {
                scale: [1.0; 3],
                offset_g: accel.map(|c| -c / 2048.0),
                gyro_bias_dps: Some(gyro.map(|c| -c / 32.8)),
            }
        }
        "adafruit-json" => {
            let v: serde_json::Value = serde_json::from_str(text).unwrap();
            Applied {
                scale: [1.0; 3],
                offset_g: vector(&v["accel_zerog"]).map(|x| x / G),
                gyro_bias_dps: Some(vector(&v["gyro_zerorate"]).map(|x| x / RAD_PER_DEG)),
            }
        }
        "kalibr" => Applied { scale: [1.0; 3], offset_g: [0.0; 3], gyro_bias_dps: None },
        other => panic!("no reader for {other}"),
    }
}

/// RMS and worst of |f(u) - u| over random unit u.
fn spread(f: impl Fn([f64; 3]) -> [f64; 3]) -> (f64, f64) {
    let points = directions(20_000);
    let errors: Vec<f64> = points
        .iter()
        .map(|u| {
            let a = f(*u);
            ((a[0] - u[0]).powi(2) + (a[1] - u[1]).powi(2) + (a[2] - u[2]).powi(2)).sqrt()
        })
        .collect();
    (
        (errors.iter().map(|e| e * e).sum::<f64>() / errors.len() as f64).sqrt(),
        errors.iter().cloned().fold(0.0, f64::max),
    )
}

/// The loss the target's values leave on the true simulated sensor: (rms mg, worst mg, gyro rms %, gyro worst %).
fn measured_on_truth(applied: &Applied) -> (f64, f64, f64, f64) {
    let sim = simulated();
    let (true_inverse, true_gyro_inverse) = (inverse(&sim.true_matrix), inverse(&sim.true_gyro_matrix));
    let accel = spread(|u| {
        let m = correct(&true_inverse, &[0.0; 3], u).map(|v| v);
        let m = [0, 1, 2].map(|i| m[i] + sim.true_offset[i]);
        [0, 1, 2].map(|i| applied.scale[i] * (m[i] - applied.offset_g[i]))
    });
    // NOTE: none of these targets has a gyro matrix: what they apply to the rate (bias aside) is G_true^-1 u.
    let gyro = spread(|u| correct(&true_gyro_inverse, &[0.0; 3], u));
    (accel.0 * 1e3, accel.1 * 1e3, gyro.0 * 1e2, gyro.1 * 1e2)
}

/// RMS and worst |G_fit G_true^-1 u - u| over rate directions, in %: the fitted G's own error.
fn gyro_fit_error_pct() -> (f64, f64) {
    let sim = simulated();
    let true_inverse = inverse(&sim.true_gyro_matrix);
    let spread = spread(|u| correct(&sim.gyro_matrix, &[0.0; 3], correct(&true_inverse, &[0.0; 3], u)));
    (spread.0 * 1e2, spread.1 * 1e2)
}

fn assert_stated_loss_is_measured(target: &str, extra: &[&str]) {
    let file = export(target, &format!("{target}.out"), extra);
    let text = read(&file);
    let stated = stated_loss(&text);
    let measured = measured_on_truth(&read_back(target, &text));
    // NOTE: the settled sensor's gyro has no scale error (G_true = I), so what dropping G loses on it is
    // the fitted G's own error; the gyro's tolerance adds that error, measured here against the truth.
    let fit_error = gyro_fit_error_pct();
    let pairs = [
        (stated.0, measured.0, 0.0, "mg rms"),
        (stated.1, measured.1, 0.0, "mg worst"),
        (stated.2, measured.2, fit_error.0, "% gyro rms"),
        (stated.3, measured.3, fit_error.1, "% gyro worst"),
    ];
    for (stated, measured, extra, what) in pairs {
        let tolerance = 0.1 * (measured + extra) + extra;
        assert!(
            (stated - measured).abs() <= tolerance,
            "{target}: stated {stated:.4} {what}, measured {measured:.4} on the true sensor"
        );
    }
}

#[test]
fn ardupilot_stated_loss_is_the_loss_on_the_true_sensor_within_10_percent() {
    assert_stated_loss_is_measured("ardupilot", &[]);
}

#[test]
fn px4_stated_loss_is_the_loss_on_the_true_sensor_within_10_percent() {
    assert_stated_loss_is_measured("px4", &[]);
}

#[test]
fn betaflight_stated_loss_is_the_loss_on_the_true_sensor_within_10_percent() {
    assert_stated_loss_is_measured("betaflight", &[]);
}

#[test]
fn inav_stated_loss_is_the_loss_on_the_true_sensor_within_10_percent() {
    assert_stated_loss_is_measured("inav", &[]);
}

#[test]
fn i2cdevlib_stated_loss_is_the_loss_on_the_true_sensor_within_10_percent() {
    assert_stated_loss_is_measured("i2cdevlib", &[]);
}

#[test]
fn adafruit_json_stated_loss_is_the_loss_on_the_true_sensor_within_10_percent() {
    assert_stated_loss_is_measured("adafruit-json", &[]);
}

#[test]
fn kalibr_stated_loss_is_the_uncalibrated_error_on_the_true_sensor_within_10_percent() {
    let noise = simulated().dir.join("noise.json");
    std::fs::write(&noise, NOISE_JSON).unwrap();
    assert_stated_loss_is_measured("kalibr", &["--noise", noise.to_str().unwrap()]);
    let yaml = read(&simulated().dir.join("kalibr.out"));
    assert!(yaml.contains("accelerometer_noise_density: 1.5e-3"), "{yaml}");
    assert!(yaml.contains("update_rate: 1000"), "{yaml}");
}

/// The part of `accelcal noise --json` the kalibr export reads.
const NOISE_JSON: &str = r#"{"sample_rate_hz": 1000.0, "kalibr": {"continuous_time": {"accelerometer_noise_density": 1.5e-3,
 "accelerometer_random_walk": 2e-4, "gyroscope_noise_density": 8e-5, "gyroscope_random_walk": 3e-6}}}"#;

#[test]
fn autopilot_and_adafruit_offsets_are_in_m_s2_with_standard_gravity_and_offsets_first() {
    let sim = simulated();
    for target in ["ardupilot", "px4", "adafruit-json"] {
        let applied = read_back(target, &read(&export(target, &format!("{target}.g"), &[])));
        for i in 0..3 {
            let error = (applied.offset_g[i] - sim.offset[i]).abs();
            assert!(
                error <= 1e-7 * sim.offset[i].abs() + 1e-12,
                "{target} axis {i}: offset {} g, calibration's {} g",
                applied.offset_g[i],
                sim.offset[i]
            );
            let bias = applied.gyro_bias_dps.unwrap()[i];
            assert!(
                (bias - sim.gyro_bias[i]).abs() <= 1e-6,
                "{target} gyro axis {i}: {bias} deg/s, calibration's {}",
                sim.gyro_bias[i]
            );
        }
    }
}

/// Adafruit_Sensor_Calibration_EEPROM's loadCalibration, written to its layout: the 16-bit CRC of all 68
/// bytes (crc16_update: init 0xFFFF, reflected polynomial 0xA001) is 0, the magic is 0x75 0x54, then 16
/// little-endian floats.
fn adafruit_load(image: &[u8]) -> Option<[f32; 16]> {
    let mut crc: u16 = 0xFFFF;
    for byte in image {
        crc ^= u16::from(*byte);
        for _ in 0..8 {
            crc = if crc & 1 == 1 { (crc >> 1) ^ 0xA001 } else { crc >> 1 };
        }
    }
    if image.len() != 68 || crc != 0 || image[0] != 0x75 || image[1] != 0x54 {
        return None;
    }
    Some(std::array::from_fn(|i| f32::from_le_bytes(image[2 + 4 * i..6 + 4 * i].try_into().unwrap())))
}

#[test]
fn adafruit_eeprom_image_is_accepted_by_the_library_layout_and_carries_the_offsets() {
    let sim = simulated();
    let image = std::fs::read(export("adafruit-eeprom", "adafruit.eeprom", &[])).unwrap();
    let floats = adafruit_load(&image).expect("the image is refused by the library's reader");
    for i in 0..3 {
        let accel = f64::from(floats[i]) / G;
        assert!(
            (accel - sim.offset[i]).abs() <= 1e-7 * sim.offset[i].abs(),
            "accel_zerog[{i}] {accel} g, calibration's {}",
            sim.offset[i]
        );
        let gyro = f64::from(floats[3 + i]) / RAD_PER_DEG;
        assert!((gyro - sim.gyro_bias[i]).abs() <= 1e-6, "gyro_zerorate[{i}] {gyro} deg/s");
    }
    assert_eq!(&floats[10..13], &[1.0; 3], "the soft-iron diagonal is neutral");
    let mut corrupted = image.clone();
    corrupted[20] ^= 1;
    assert!(adafruit_load(&corrupted).is_none(), "the reader must refuse a corrupted image");
}

#[test]
fn binary_target_without_output_file_is_refused_with_the_way_out() {
    let output = accelcal(&["export", simulated().json.to_str().unwrap(), "--to", "adafruit-eeprom"]);
    assert!(!output.status.success());
    assert!(output.stdout.is_empty(), "nothing binary on stdout");
    let error = String::from_utf8_lossy(&output.stderr);
    assert!(error.contains("binary") && error.contains("-o FILE"), "{error}");
}

#[test]
fn count_targets_write_the_calibrations_offset_to_half_a_step_with_the_sign_their_firmware_applies() {
    let sim = simulated();
    // NOTE: i2cdevlib's accelerometer registers step by 2 counts: bit 0 is reserved (InvenSense, MPU
    // Hardware Offset Registers Application Note), so half a step is a whole count there.
    for (target, counts_per_g, step) in [("betaflight", 2048.0, 1.0), ("inav", 4096.0, 1.0), ("i2cdevlib", 2048.0, 2.0)]
    {
        let applied = read_back(target, &read(&export(target, &format!("{target}.sign"), &[])));
        for i in 0..3 {
            let error = (applied.offset_g[i] - sim.offset[i]).abs() * counts_per_g;
            assert!(
                error <= step / 2.0 + 1e-9,
                "{target} axis {i}: offset {} g, calibration's {} g",
                applied.offset_g[i],
                sim.offset[i]
            );
        }
    }
}

#[test]
fn i2cdevlib_states_what_imu_zeros_one_pose_offsets_would_leave_within_10_percent() {
    let sim = simulated();
    let text = read(&export("i2cdevlib", "i2cdevlib.imu_zero", &[]));
    let stated = numbers_after_label(text.lines().find(|l| l.contains("IMU_Zero")).expect("an IMU_Zero line"));
    // IMU_Zero zeroes the true sensor's reading at +Z up to 0, 0, 1 g.
    let up = correct(&inverse(&sim.true_matrix), &[0.0; 3], [0.0, 0.0, 1.0]);
    let offset = [0, 1, 2].map(|i| up[i] + sim.true_offset[i] - [0.0, 0.0, 1.0][i]);
    let applied = Applied { scale: [1.0; 3], offset_g: offset, gyro_bias_dps: None };
    let measured = measured_on_truth(&applied);
    for (stated, measured, what) in [(stated[0], measured.0, "rms"), (stated[1], measured.1, "worst")] {
        assert!(
            (stated - measured).abs() <= 0.1 * measured,
            "IMU_Zero: stated {stated:.4} mg {what}, measured {measured:.4}"
        );
    }
}

/// The decimal numbers of a line after its label (up to "):").
fn numbers_after_label(line: &str) -> Vec<f64> {
    let tail = &line[line.find("):").map_or(0, |i| i + 2)..];
    tail.split(|c: char| !(c.is_ascii_digit() || c == '.'))
        .filter(|s| !s.is_empty())
        .filter_map(|s| s.parse().ok())
        .collect()
}
