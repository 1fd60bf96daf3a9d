//! `accelcal noise FILE --json --plot FILE.svg` as a user runs it: the JSON interface of the design,
//! in the units it names, on a recording with known white noise.

use std::fmt::Write;
use std::process::Command;

use accelcal::sim::noise::{noisy_series, TrueNoise};

const RATE_HZ: f64 = 1000.0;
const ACCEL_DENSITY_G: f64 = 400e-6;
const GYRO_DENSITY_DPS: f64 = 0.005;

/// A minute of white noise on all six axes, as `accelcal stream` writes it, in a file of its own
/// for each test (`name`).
fn white_recording(name: &str) -> std::path::PathBuf {
    let samples = 60_000;
    let white = |density: f64, mean: f64, seed: u64| {
        let truth = TrueNoise { white_noise_density: density, bias_instability: 0.0, random_walk: 0.0 };
        noisy_series(&truth, mean, RATE_HZ, samples, seed)
    };
    let axes: Vec<Vec<f64>> = (0..6u64)
        .map(|k| if k < 3 { white(ACCEL_DENSITY_G, 0.0, k) } else { white(GYRO_DENSITY_DPS, 0.5, k) })
        .collect();
    let mut text = String::from("index,ax_g,ay_g,az_g,gx_dps,gy_dps,gz_dps,temp_c\n");
    for i in 0..samples {
        let row: Vec<String> = axes.iter().map(|a| format!("{:.9}", a[i])).collect();
        let _ = writeln!(text, "{i},{},25.0", row.join(","));
    }
    let path = std::env::temp_dir().join(format!("accelcal-noise-{}-{name}.csv", std::process::id()));
    std::fs::write(&path, text).expect("temporary recording written");
    path
}

fn close(value: &serde_json::Value, truth: f64, tolerance: f64) -> bool {
    value.as_f64().is_some_and(|v| (v / truth - 1.0).abs() < tolerance)
}

#[test]
fn noise_json_has_every_axis_in_its_named_units_and_finds_the_white_noise() {
    let recording = white_recording("json");
    let plot = recording.with_extension("svg");
    let output = Command::new(env!("CARGO_BIN_EXE_accelcal"))
        .args(["noise", &recording.display().to_string(), "--json", "--plot", &plot.display().to_string()])
        .output()
        .expect("accelcal runs");
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).expect("stdout is one JSON object");
    for axis in ["accel_x", "accel_y", "accel_z", "gyro_x", "gyro_y", "gyro_z"] {
        let a = &json[axis];
        let n = a["tau_s"].as_array().map_or(0, Vec::len);
        assert!(n >= 30, "{axis}: {n} averaging times");
        for key in ["adev", "adev_low", "adev_high"] {
            assert_eq!(a[key].as_array().map_or(0, Vec::len), n, "{axis}.{key}");
        }
        let (low, dev, high) = (a["adev_low"][0].as_f64(), a["adev"][0].as_f64(), a["adev_high"][0].as_f64());
        assert!(low < dev && dev < high, "{axis}: interval {low:?} {dev:?} {high:?}");
        for key in ["bias_instability", "bias_instability_tau_s", "random_walk"] {
            assert!(a[key].is_number(), "{axis}.{key}");
        }
    }
    // The usual units: ug/sqrt(Hz) for the accelerometer, deg/s/sqrt(Hz) for the gyro.
    assert_eq!(json["units"]["accel_y"]["white_noise_density"], "ug/sqrt(Hz)");
    assert_eq!(json["units"]["gyro_y"]["white_noise_density"], "deg/s/sqrt(Hz)");
    assert!(close(&json["accel_x"]["white_noise_density"], ACCEL_DENSITY_G * 1e6, 0.05), "{}", json["accel_x"]);
    assert!(close(&json["gyro_z"]["white_noise_density"], GYRO_DENSITY_DPS, 0.05), "{}", json["gyro_z"]);
    // Kalibr's continuous-time density is SI, m/s^2/sqrt(Hz), and two-sided: the datasheet's / sqrt(2).
    let kalibr = &json["kalibr"]["continuous_time"]["accelerometer_noise_density"];
    assert!(close(kalibr, ACCEL_DENSITY_G * 9.80665 / 2f64.sqrt(), 0.05), "{kalibr}");
    // White noise resolves no random walk: Kalibr gets the largest the curve allows, sigma sqrt(3 / tau)
    // at the longest tau (68 % upper end), in m/s^3/sqrt(Hz) from the curve's ug.
    assert_eq!(json["kalibr"]["accelerometer_random_walk_resolved"], false, "{}", json["kalibr"]);
    let bound = |axis: &str| {
        let (tau, high) = (&json[axis]["tau_s"], &json[axis]["adev_high"]);
        let last = tau.as_array().unwrap().len() - 1;
        high[last].as_f64().unwrap() * (3.0 / tau[last].as_f64().unwrap()).sqrt() * 1e-6 * 9.80665
    };
    let largest = ["accel_x", "accel_y", "accel_z"].map(bound).into_iter().fold(0.0, f64::max);
    let given = json["kalibr"]["continuous_time"]["accelerometer_random_walk"].as_f64().unwrap();
    assert!((given / largest - 1.0).abs() < 1e-9, "{given} against the bound {largest}");
    // White noise keeps falling: the capture limit is only a lower bound, the longest tau analysed.
    assert_eq!(json["calibration"]["capture_limit_is_lower_bound"], true, "{}", json["calibration"]);
    // The one schema reads back what it wrote, every number where the untyped object has it.
    let typed = accelcal::noise::json::read(&String::from_utf8_lossy(&output.stdout)).expect("read typed");
    for axis in ["accel_x", "accel_y", "accel_z", "gyro_x", "gyro_y", "gyro_z"] {
        let read = typed.axis(axis).expect("every axis");
        assert_eq!(read.white_noise_density, json[axis]["white_noise_density"].as_f64(), "{axis}");
        assert_eq!(read.adev.len(), json[axis]["adev"].as_array().map_or(0, Vec::len), "{axis}");
        assert_eq!(read.bias_instability_resolved, json[axis]["bias_instability_resolved"] == true, "{axis}");
    }
    assert!(typed.calibration.capture_limit_is_lower_bound && typed.sample_rate_hz == Some(RATE_HZ));
    let kalibr = typed.kalibr.expect("kalibr").continuous_time.accelerometer_noise_density;
    assert_eq!(Some(kalibr), json["kalibr"]["continuous_time"]["accelerometer_noise_density"].as_f64());
    let svg = std::fs::read_to_string(&plot).expect("the plot is written");
    assert!(svg.starts_with("<svg") && svg.contains("gyro_z"), "{}", &svg[..svg.len().min(200)]);
    let _ = (std::fs::remove_file(recording), std::fs::remove_file(plot));
}

#[test]
fn an_older_noise_report_without_the_newer_fields_still_reads() {
    // Written before `bias_instability_resolved`, `adev_low`/`adev_high` and `kalibr.discrete_time`.
    let old = r#"{"sample_rate_hz": 100.0, "samples": 6000,
        "accel_x": {"tau_s": [0.01, 0.1], "adev": [300.0, 95.0], "white_noise_density": 42.0},
        "kalibr": {"continuous_time": {"accelerometer_noise_density": 1e-3, "accelerometer_random_walk": 2e-4,
        "gyroscope_noise_density": 8e-5, "gyroscope_random_walk": 3e-6}}}"#;
    let report = accelcal::noise::json::read(old).expect("an older report reads");
    let axis = report.axis("accel_x").unwrap();
    assert!(axis.bias_instability_resolved, "older reports did not say: taken as resolved");
    assert_eq!((axis.white_noise_density, axis.adev.len()), (Some(42.0), 2));
    assert!(report.axis("gyro_z").unwrap_err().contains("it has no gyro_z"));
    assert!(report.calibration.capture_limit_s.is_none() && !report.calibration.capture_limit_is_lower_bound);
    assert!(report.kalibr.unwrap().discrete_time.is_none());
}

#[test]
fn a_position_longer_than_the_recording_resolves_is_not_predicted() {
    let recording = white_recording("positions");
    let run = |json: bool| {
        let mut args = vec!["noise".to_owned(), recording.display().to_string()];
        args.extend(json.then(|| "--json".to_owned()));
        let output = Command::new(env!("CARGO_BIN_EXE_accelcal")).args(&args).output().expect("accelcal runs");
        assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
        String::from_utf8(output.stdout).unwrap()
    };
    let json: serde_json::Value = serde_json::from_str(&run(true)).unwrap();
    let longest = json["accel_x"]["tau_s"].as_array().unwrap().last().unwrap().as_f64().unwrap();
    // NOTE: a minute resolves averaging times up to a tenth of it.
    assert!((5.0..=6.0).contains(&longest), "longest {longest} s");
    let text = run(false);
    for seconds in [1, 2, 5, 10, 30, 60] {
        let line =
            text.lines().find(|l| l.starts_with(&format!("a {seconds:>3} s position"))).expect("every length shown");
        let predicted = line.contains("mean known to");
        assert_eq!(predicted, f64::from(seconds) <= longest, "{line}");
        assert!(predicted || line.contains(&format!("record at least {} s", 10 * seconds)), "{line}");
    }
    let _ = std::fs::remove_file(recording);
}
