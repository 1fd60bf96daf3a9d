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

/// Reference rows in m/s^2: the six faces and two tilts, each reading a little off its reference.
fn reference_rows_in_ms2() -> String {
    let faces =
        [[1.0, 0.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, 1.0], [0.0, 0.0, -1.0]];
    let (h, t) = (std::f64::consts::FRAC_1_SQRT_2, 1.0 / 3f64.sqrt());
    let tilts = [[h, 0.0, h], [0.0, -h, h], [t, t, t]];
    let mut text = String::from("x,y,z,ref_x,ref_y,ref_z\n");
    for up in faces.iter().chain(&tilts) {
        let reference = up.map(|v| v * 9.80665);
        let reading = [reference[0] * 1.01 + 0.2, reference[1] * 0.99 - 0.1, reference[2] * 1.005 + 0.05];
        let cells: Vec<String> = reading.iter().chain(&reference).map(|v| format!("{v:.5}")).collect();
        text += &(cells.join(",") + "\n");
    }
    text
}

#[test]
fn reference_rows_the_size_of_gravity_in_ms2_are_refused_naming_g_and_fitted_with_it() {
    let dir = scratch("reference-ms2");
    let file = dir.join("imucal.csv");
    std::fs::write(&file, reference_rows_in_ms2()).unwrap();
    let output = accelcal(&["fit", path(&file)]);
    let said = text(&output.stderr);
    assert!(!output.status.success(), "{said}");
    assert!(said.contains("the references have a size of 9.8066, gravity's in m/s^2, where --g is 1"), "{said}");
    assert!(said.contains("give --g 9.81") && !said.contains("richer model"), "{said}");
    let fitted: Value = serde_json::from_str(&stdout_of(&["fit", path(&file), "--g", "9.80665", "--json"])).unwrap();
    let offset = fitted["offset"].as_array().unwrap();
    assert!((offset[0].as_f64().unwrap() - 0.2).abs() < 1e-3, "{fitted}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Each kind of file that is no sensor's stream, and what `fit`'s refusal must say of it: its cause
/// and the fix, never a wrong baud rate for text nor a data file's missing columns.
#[test]
fn each_refused_kind_of_file_is_named_with_what_it_is_and_the_fix() {
    let dir = scratch("refused-kinds");
    let binary: Vec<u8> = (0..4000u32).map(|i| (i.wrapping_mul(2_654_435_761) >> 13) as u8).collect();
    let web_log = "2026-11-28 10:00:01 GET /index.html 200 1234\n2026-11-28 10:00:02 GET /a.css 200 99\n".repeat(50);
    let source = "fn main() {\n    println!(\"hello\");\n}\n".repeat(30);
    let two = (0..100).map(|k| format!("{},{}\n", 12 + k % 3, 340 - k % 5)).collect::<String>();
    let cases: [(&str, Vec<u8>, &[&str]); 4] = [
        ("binary.bin", binary, &["over a quarter of it is bytes that are not text", "a binary file"]),
        ("server.log", web_log.into_bytes(), &["line 1 `2026-11-28 10:00:01 GET", "a log or another program's text"]),
        ("main.rs", source.into_bytes(), &["words and no number (line 1: `fn main() {`)", "another program's text"]),
        (
            "two.csv",
            two.into_bytes(),
            &["line 1 `12,340` holds 2 values and no line holds three", "Serial.println(az)"],
        ),
    ];
    for (name, bytes, wanted) in cases {
        let file = dir.join(name);
        std::fs::write(&file, bytes).unwrap();
        let output = accelcal(&["fit", path(&file)]);
        let said = text(&output.stderr);
        assert!(!output.status.success(), "{name}: {said}");
        for words in wanted {
            assert!(said.contains(words), "{name}: {said}");
        }
        assert!(!said.contains("no reading columns"), "{name}: {said}");
        assert!(name == "binary.bin" || !said.contains("baud"), "{name}: {said}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
