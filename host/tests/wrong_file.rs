//! A file given to the command next door (issue 40): `report` names another accelcal JSON and the
//! command that takes it, `upload` takes the session file `export` takes, and `fit` reads
//! accelcal's own `stream` CSV as it reads a sketch's log.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use accelcal::sim::person::PersonSession;
use accelcal::sim::sketch::Sketch;
use serde_json::Value;

fn accelcal(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_accelcal")).args(args).output().expect("accelcal runs")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("accelcal-wrong-file-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `accelcal ARGS`, succeeded; what it printed on stdout.
fn stdout_of(args: &[&str]) -> String {
    let output = accelcal(args);
    assert!(output.status.success(), "{args:?}: {}", text(&output.stderr));
    text(&output.stdout)
}

fn path(path: &Path) -> &str {
    path.to_str().unwrap()
}

#[test]
fn a_thermal_or_noise_json_given_to_report_as_the_session_is_named_with_the_command_that_takes_it() {
    let dir = scratch("report");
    let (thermal, recording, noise) = (dir.join("thermal.json"), dir.join("rec.npy"), dir.join("noise.json"));
    std::fs::write(&thermal, stdout_of(&["thermal", "--sim", "--json"])).unwrap();
    stdout_of(&["record", "--sim", "--seconds", "2", "-o", path(&recording)]);
    std::fs::write(&noise, stdout_of(&["noise", path(&recording), "--json"])).unwrap();
    for (file, what, option) in [
        (&thermal, "the temperature model `accelcal thermal --json` printed", "--thermal FILE"),
        (&noise, "a noise report (`accelcal noise --json`)", "--noise FILE"),
    ] {
        let output = accelcal(&["report", path(file)]);
        let said = text(&output.stderr);
        assert!(!output.status.success(), "{said}");
        assert!(said.contains(&format!("{} is not a session but {what}", file.display())), "{said}");
        assert!(said.contains(&format!("`accelcal report SESSION.json {option}`")), "{said}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn upload_takes_the_session_file_export_takes_and_uploads_the_calibration_calibrate_uploaded() {
    let dir = scratch("upload");
    let stem = dir.join("board");
    let calibrated =
        stdout_of(&["calibrate", "--sim", "--chip-fit", "--yes", "--seed", "3", "--session", path(&stem), "--json"]);
    let calibrated: Value = serde_json::from_str(&calibrated).unwrap();
    let record = dir.join("calibration.json");
    std::fs::write(&record, calibrated["calibration"].to_string()).unwrap();
    let from_record = stdout_of(&["upload", "--sim", path(&record)]);
    let from_session = stdout_of(&["upload", "--sim", path(&stem.with_extension("json"))]);
    assert!(from_record.starts_with("uploaded ortho9: scale"), "{from_record}");
    assert_eq!(from_session, from_record);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A simulated person's session (seed 5) as `accelcal stream` writes it: the samples in g and deg/s,
/// with the board's serial last.
fn own_stream_csv(session: &PersonSession) -> String {
    let mut csv = "index,time_s,ax_g,ay_g,az_g,gx_dps,gy_dps,gz_dps,temp_c,board\n".to_owned();
    for (i, s) in session.samples.iter().enumerate() {
        let [ax, ay, az] = s.accel.map(|c| f64::from(c) / 16384.0);
        let [gx, gy, gz] = s.gyro.map(|c| f64::from(c) / 131.0);
        csv.push_str(&format!(
            "{i},{:.6},{ax:.6},{ay:.6},{az:.6},{gx:.4},{gy:.4},{gz:.4},25.00,53494D000000000000000005\n",
            s.at_s
        ));
    }
    csv
}

#[test]
fn fit_reads_accelcal_s_own_stream_csv_as_it_reads_the_same_samples_in_a_sketch_s_log() {
    let dir = scratch("fit");
    let session = PersonSession::new(5, Sketch::Csv.reading());
    let (own, sketch) = (dir.join("stream.csv"), dir.join("sketch.csv"));
    std::fs::write(&own, own_stream_csv(&session)).unwrap();
    std::fs::write(&sketch, Sketch::Csv.lines(&session).into_iter().map(|l| l.text).collect::<String>()).unwrap();
    let fitted = |file: &Path| -> Value { serde_json::from_str(&stdout_of(&["fit", path(file), "--json"])).unwrap() };
    let (own, sketch) = (fitted(&own), fitted(&sketch));
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!((&own["input_unit"], &sketch["input_unit"]), (&Value::from("g"), &Value::from("counts-2g")));
    for key in ["samples", "rate_hz", "rate_source", "model"] {
        assert_eq!(own[key], sketch[key], "{key}");
    }
    assert_eq!(own["segments"].as_array().map(Vec::len), sketch["segments"].as_array().map(Vec::len));
    // The same calibration: M in g per g is 16384 times M in g per count, o in g o in counts / 16384.
    let entries = |json: &Value, key: &str| -> Vec<f64> {
        let flat = json[key].as_array().unwrap().iter().flat_map(|v| v.as_array().cloned().unwrap_or(vec![v.clone()]));
        flat.map(|v| v.as_f64().unwrap()).collect()
    };
    for (own_m, counts_m) in entries(&own, "matrix").iter().zip(entries(&sketch, "matrix")) {
        assert!((own_m - counts_m * 16384.0).abs() < 1e-5, "M: {own_m} against {}", counts_m * 16384.0);
    }
    for (own_o, counts_o) in entries(&own, "offset").iter().zip(entries(&sketch, "offset")) {
        assert!((own_o - counts_o / 16384.0).abs() < 1e-5, "o: {own_o} g against {} g", counts_o / 16384.0);
    }
}
