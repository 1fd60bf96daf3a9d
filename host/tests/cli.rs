//! The `accelcal` binary as a user runs it: output on success, one line naming the cause on failure.

mod common;

use common::SimPty;

use std::process::{Command, Output};

fn accelcal(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_accelcal")).args(args).output().expect("accelcal runs")
}

fn phone_data() -> String {
    format!("{}/../tests/data/huawei-phone-13.csv", env!("CARGO_MANIFEST_DIR"))
}

fn write_temp(name: &str, text: &str) -> std::path::PathBuf {
    let path = std::env::temp_dir().join(format!("accelcal-cli-{}-{name}", std::process::id()));
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn fit_json_has_the_fields_of_the_design_interface() {
    let output = accelcal(&["fit", &phone_data(), "--model", "six-position", "--g", "9.81", "--json"]);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).expect("stdout is one JSON object");
    assert_eq!(json["model"], "six-position");
    let matrix = json["matrix"].as_array().unwrap();
    assert_eq!(matrix.len(), 3);
    // A phone accelerometer's scale is within a few percent of unity.
    let m11 = matrix[0][0].as_f64().unwrap();
    assert!((m11 - 1.0).abs() < 0.05, "M11 = {m11}");
    assert_eq!(json["offset"].as_array().unwrap().len(), 3);
    assert!(json["cost"].as_f64().unwrap() > 0.0);
    assert_eq!(json["iterations"], 0);
    assert_eq!(json["parameters"].as_object().unwrap().len(), 12);
    assert!(json["parameters"]["o_z"]["std_error"].as_f64().unwrap() > 0.0);
}

/// Issue 40: `fit --json` wrote `parameters` as name -> value (standard errors in three more maps),
/// `report --json` as a list and `calibrate --json` only `std_errors`: each now writes the one form,
/// an object keyed by name whose entries carry the same four fields, as a certificate's are keyed.
#[test]
fn fit_report_and_calibrate_json_write_parameters_in_one_form() {
    let dir = std::env::temp_dir().join(format!("accelcal-cli-{}-forms", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let session = dir.join("s.json");
    let run = accelcal(&["calibrate", "--sim", "--yes", "--json", "--session", session.to_str().unwrap()]);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let json =
        |output: &Output| -> serde_json::Value { serde_json::from_slice(&output.stdout).expect("one JSON object") };
    let calibrated = json(&run)["host_fit"]["parameters"].clone();
    let reported = json(&accelcal(&["report", session.to_str().unwrap(), "--json"]))["fit"]["parameters"].clone();
    let fitted = json(&accelcal(&["fit", &phone_data(), "--g", "9.81", "--json"]))["parameters"].clone();
    let fields = ["noise_std_error", "scatter_std_error", "std_error", "value"];
    for (what, parameters) in [("calibrate", &calibrated), ("report", &reported), ("fit", &fitted)] {
        let by_name = parameters.as_object().unwrap_or_else(|| panic!("{what}: parameters is {parameters}"));
        assert!(by_name.len() >= 6, "{what}: {} parameters", by_name.len());
        for (name, entry) in by_name {
            let keys: Vec<&str> = entry.as_object().unwrap().keys().map(String::as_str).collect();
            assert_eq!(keys, fields, "{what}: {name}");
            assert!(entry["value"].is_f64(), "{what}: {name} = {entry}");
        }
    }
    // The session's report refits the captures the run fitted: the same parameters.
    assert_eq!(
        calibrated.as_object().unwrap().keys().collect::<Vec<_>>(),
        reported.as_object().unwrap().keys().collect::<Vec<_>>()
    );
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn fit_auto_prints_the_best_predicting_fit_why_with_errors_before_and_after_and_the_comparison() {
    let output = accelcal(&["fit", &phone_data(), "--g", "9.81"]);
    assert!(output.status.success());
    let text = String::from_utf8(output.stdout).unwrap();
    // auto: the model that best predicts left-out rows of the 13 orientation-free rows (diag6 at
    // 1.886 mg against ortho9 at 2.805 mg, tests/model_selection.rs), why, then every model.
    assert!(text.starts_with("model diag6 (13 of 13 rows used)"), "{text}");
    assert!(text.contains("auto: diag6 predicts rows it did not see best: | |a| - g | 1.886 mg RMS"), "{text}");
    assert!(text.contains("worst ||a|-g|:"), "{text}");
    assert!(text.contains("model comparison"), "{text}");
    assert!(text.contains("linear12          not supported: linear12 needs at least 4 rows"), "{text}");
}

#[test]
fn a_bad_file_fails_with_one_line_naming_the_line_and_cause() {
    let path = write_temp("bad.csv", "x,y,z\n1,2,3\n1,oops,3\n");
    let output = accelcal(&["fit", path.to_str().unwrap()]);
    assert!(!output.status.success());
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("line 3, column y: \"oops\" is not a number"), "{stderr}");
}

#[test]
fn a_file_without_references_is_refused_for_linear12_with_what_to_add() {
    let output = accelcal(&["fit", &phone_data(), "--model", "linear12", "--g", "9.81"]);
    assert!(!output.status.success());
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert!(
        stderr.contains("linear12 needs at least 4 rows with a known orientation (ref_x,ref_y,ref_z); the file has 0"),
        "{stderr}"
    );
}

#[test]
fn a_missing_file_and_an_unknown_model_are_named() {
    let output = accelcal(&["fit", "/nonexistent/data.csv"]);
    assert!(String::from_utf8(output.stderr).unwrap().contains("cannot read /nonexistent/data.csv"));
    let output = accelcal(&["fit", &phone_data(), "--model", "quadratic"]);
    assert!(!output.status.success());
    assert!(String::from_utf8(output.stderr).unwrap().contains("unknown model \"quadratic\""));
}

#[test]
fn calibrate_sim_json_has_calibration_truth_and_verification() {
    // NOTE: sub-mg claims need one temperature: the settled sensor (the realistic one warms during
    // the session; see the test below for what that costs).
    let output = accelcal(&["calibrate", "--sim", "--sim-sensor", "settled", "--json", "--seed", "3"]);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).expect("one JSON object");
    assert_eq!(json["calibration"]["model"], "ortho9");
    // The fitted correction is the simulated sensor's true one, to within its noise.
    for i in 0..3 {
        let fitted = json["calibration"]["offset"][i].as_f64().unwrap();
        let truth = json["truth"]["offset"][i].as_f64().unwrap();
        assert!((fitted - truth).abs() < 0.5e-3, "offset {i}: {fitted} vs {truth}");
        for j in 0..3 {
            let fitted = json["calibration"]["matrix"][i][j].as_f64().unwrap();
            let truth = json["truth"]["matrix"][i][j].as_f64().unwrap();
            assert!((fitted - truth).abs() < 1e-3, "M{i}{j}: {fitted} vs {truth}");
        }
    }
    assert!(json["truth"]["drift"].is_null(), "the settled sensor does not drift: {}", json["truth"]);
    let verification = &json["verification"];
    // The default session verifies at three orientations, each as long as the 0.2 mg target needs;
    // the board's time from the first capture to the end: measured 55.9 s for this seed.
    assert_eq!(verification["positions"], 3);
    let board_seconds = json["board_seconds"].as_f64().unwrap();
    assert!((40.0..60.0).contains(&board_seconds), "board_seconds {board_seconds}");
    assert!(verification["before_rms_mg"].as_f64().unwrap() > 10.0, "{verification}");
    assert!(verification["after_rms_mg"].as_f64().unwrap() < 1.0, "{verification}");
    assert!(verification["after_max_mg"].as_f64().unwrap() < 1.0, "{verification}");
}

#[test]
fn calibrate_sim_on_the_realistic_sensor_that_warms_during_the_session_verifies_within_2_5_mg() {
    // The default simulated board has just been powered on: its die warms from 20 degC during the
    // session, so the offsets drift while the positions are captured. Measured with the adaptive
    // session and its fitted drift: 0.13-0.71 mg rms after calibration over seeds 1-5 at 3 fresh
    // orientations (1.07-1.63 mg with 14 fixed 10 s captures and no drift model before issue 16).
    let output = accelcal(&["calibrate", "--sim", "--json", "--seed", "1"]);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).expect("one JSON object");
    let verification = &json["verification"];
    assert!(verification["before_rms_mg"].as_f64().unwrap() > 10.0, "{verification}");
    assert!(verification["after_rms_mg"].as_f64().unwrap() < 2.5, "{verification}");
    truth_is_the_sensor_at_the_calibration_s_temperature(&json);
}

/// `truth` holds at the calibration's temperature, so it compares with `calibration` directly (its
/// static truth at 25 degC was 4.5 mg away), has one gyro bias, and its drift gives it back.
fn truth_is_the_sensor_at_the_calibration_s_temperature(json: &serde_json::Value) {
    let (calibration, truth) = (&json["calibration"], &json["truth"]);
    let temp_c = truth["temp_c"].as_f64().unwrap();
    // NOTE: the same f32, printed once as f32 and once as f64.
    assert!((temp_c - calibration["mean_temp_c"].as_f64().unwrap()).abs() < 1e-5, "{truth}");
    let value = |v: &serde_json::Value| v.as_f64().unwrap();
    for k in 0..3 {
        let (fitted, true_g) = (value(&calibration["offset"][k]), value(&truth["offset"][k]));
        assert!((fitted - true_g).abs() < 0.5e-3, "offset {k}: {fitted} vs {true_g} at {temp_c} degC");
    }
    assert!(truth.get("gyro_bias_dps").is_none() && truth["gyro"]["bias_dps"].is_array(), "{truth}");
    // Whoever wants the truth at another temperature has it from the drift: here, at this one.
    let drift = &truth["drift"];
    let dt = temp_c - value(&drift["reading_offset_c"]) - value(&drift["ref_die_c"]);
    let poly = |key: &str, k: usize| value(&drift[key][0][k]) * dt + value(&drift[key][1][k]) * dt * dt;
    for k in 0..3 {
        let offset = value(&drift["ref_offset"][k]) + poly("offset_g", k);
        assert!((offset - value(&truth["offset"][k])).abs() < 1e-6, "offset {k} from the drift: {offset}");
        let bias = value(&drift["ref_gyro_bias_dps"][k]) + poly("gyro_bias_dps", k);
        assert!((bias - value(&truth["gyro"]["bias_dps"][k])).abs() < 1e-5, "gyro bias {k} from the drift: {bias}");
        for i in 0..3 {
            let matrix = value(&drift["ref_matrix"][i][k]) / (1.0 + poly("scale", k));
            assert!((matrix - value(&truth["matrix"][i][k])).abs() < 1e-6, "M{i}{k} from the drift: {matrix}");
        }
    }
}

#[test]
fn thermal_sim_json_compensates_15_to_45_degc_to_within_1_mg_where_the_static_calibration_errs_by_10() {
    let output = accelcal(&["thermal", "--sim", "--json", "--seed", "2"]);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).expect("one JSON object");
    assert!(json["calibration"]["temperature"]["ref_temp_c"].as_f64().is_some(), "{}", json["calibration"]);
    let rows = json["verification"].as_array().expect("verification rows");
    let temps: Vec<f64> = rows.iter().map(|r| r["temp_c"].as_f64().unwrap()).collect();
    for (got, want) in temps.iter().zip([15.0, 25.0, 35.0, 45.0]) {
        assert!((got - want).abs() < 0.5, "verified at {temps:?}");
    }
    for row in rows {
        let compensated = row["compensated_rms_mg"].as_f64().unwrap();
        assert!(compensated <= 1.0, "with the temperature model: {row}");
        // The chip's offset at that temperature is the true one to within 1 mg.
        for k in 0..3 {
            let (applied, truth) = (row["applied_offset"][k].as_f64().unwrap(), row["offset"][k].as_f64().unwrap());
            assert!(
                (applied - truth).abs() < 1e-3,
                "offset {k}: applied {applied} vs true {truth} at {}",
                row["temp_c"]
            );
        }
        for key in ["matrix", "applied_matrix", "static_matrix", "static_offset", "uncompensated_rms_mg"] {
            assert!(!row[key].is_null(), "{key} missing from {row}");
        }
    }
    let hot = &rows[3];
    // The sensitivity drift was learned too: at 45 degC the chip's scale is the true one to 5e-4,
    // where the static one is off by more than 2e-3 on z (1.6e-4/degC over 20 degC).
    let diag = |key: &str, k: usize| hot[key][k][k].as_f64().unwrap();
    for k in 0..3 {
        let error = (diag("applied_matrix", k) - diag("matrix", k)).abs();
        assert!(error < 5e-4, "scale {k} at 45 degC off by {error}");
    }
    assert!((diag("static_matrix", 2) - diag("matrix", 2)).abs() > 2e-3, "{hot}");
    assert!(hot["uncompensated_rms_mg"].as_f64().unwrap() >= 10.0, "the static calibration at 45 degC: {hot}");
    assert!(hot["gyro_bias_error_dps"].as_f64().unwrap() <= 0.05, "gyro bias at 45 degC: {hot}");
}

#[test]
fn no_device_on_the_port_is_one_line_naming_the_port_and_the_fix() {
    let output = accelcal(&["info", "--port", "/dev/accelcal-no-such-port"]);
    assert!(!output.status.success());
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.starts_with("accelcal: cannot open /dev/accelcal-no-such-port: "), "{stderr}");
    assert!(stderr.contains("check the cable and the path (`accelcal ports` lists the ports)"), "{stderr}");
}

#[test]
fn a_silent_port_is_an_error_within_a_few_seconds_not_a_hang() {
    let (_master, slave) = serialport::TTYPort::pair().unwrap();
    let path = serialport::SerialPort::name(&slave).unwrap();
    let started = std::time::Instant::now();
    let output = accelcal(&["info", "--port", &path]);
    let elapsed = started.elapsed();
    assert!(!output.status.success());
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert!(stderr.starts_with("accelcal: no answer from the device within 2 s"), "{stderr}");
    // NOTE: a bound on a hang, not a timing measurement: 2 s of silence plus process start-up.
    assert!(elapsed < std::time::Duration::from_secs(10), "took {elapsed:?}");
}

#[test]
fn a_device_of_another_protocol_version_is_named_with_what_to_update() {
    use std::io::{Read, Write};
    let (mut master, slave) = serialport::TTYPort::pair().unwrap();
    let path = serialport::SerialPort::name(&slave).unwrap();
    // A device answering every frame with a well-formed frame of protocol version 2.
    let fake = std::thread::spawn(move || {
        let mut buffer = [0u8; 256];
        serialport::SerialPort::set_timeout(&mut master, std::time::Duration::from_secs(5)).unwrap();
        let mut delimiters = 0;
        while let Ok(n) = master.read(&mut buffer) {
            delimiters += buffer[..n].iter().filter(|b| **b == 0).count();
            if delimiters >= 2 {
                break; // the opening delimiter and the end of the hello frame
            }
        }
        let mut raw = vec![shared::protocol::PROTOCOL_VERSION + 1, 1, 0, 9];
        let crc = crc::Crc::<u32>::new(&crc::CRC_32_ISO_HDLC).checksum(&raw);
        raw.extend_from_slice(&crc.to_le_bytes());
        let mut frame = vec![0u8; 64];
        let len = cobs::encode(&raw, &mut frame);
        frame.truncate(len);
        frame.push(0);
        let _ = master.write_all(&frame);
        std::thread::sleep(std::time::Duration::from_millis(500));
    });
    let output = accelcal(&["info", "--port", &path]);
    fake.join().unwrap();
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert_eq!(
        stderr.trim_end(),
        format!(
            "accelcal: the device speaks protocol version {}, this accelcal speaks {}: update accelcal",
            shared::protocol::PROTOCOL_VERSION + 1,
            shared::protocol::PROTOCOL_VERSION
        )
    );
}

#[test]
fn sim_pty_prints_its_path_and_speaks_the_board_protocol() {
    let sim = SimPty::with_seed("4", &[]);
    assert!(sim.path.starts_with("/dev/pts/"), "{}", sim.path);
    let output = accelcal(&["info", "--port", &sim.path, "--json"]);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    assert_eq!(json["sensor"]["address"], 0x68);
    assert_eq!(json["protocol_version"], shared::protocol::PROTOCOL_VERSION);
    assert_eq!(json["active"], serde_json::Value::Null);
}

/// Uploads `file` to the board at `port` and returns what `download` then prints.
fn upload_then_download(port: &str, file: &std::path::Path) -> serde_json::Value {
    let output = accelcal(&["upload", "--port", port, file.to_str().unwrap()]);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let output = accelcal(&["download", "--port", port]);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    serde_json::from_slice(&output.stdout).expect("download prints one JSON object")
}

/// The largest difference between the matrices and offsets of two calibration objects.
fn largest_difference(a: &serde_json::Value, b: &serde_json::Value) -> f64 {
    let numbers = |v: &serde_json::Value| -> Vec<f64> {
        let matrix = v["matrix"].as_array().unwrap().iter().flat_map(|row| row.as_array().unwrap().clone());
        matrix.chain(v["offset"].as_array().unwrap().clone()).map(|x| x.as_f64().unwrap()).collect()
    };
    let (a, b) = (numbers(a), numbers(b));
    assert_eq!((a.len(), b.len()), (12, 12));
    a.iter().zip(&b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max)
}

#[test]
fn upload_takes_what_download_fit_json_and_calibrate_json_write() {
    let sim = SimPty::with_seed("5", &[]);
    // calibrate --json: the calibration is the object under "calibration".
    let calibrated = accelcal(&["calibrate", "--sim", "--json", "--seed", "5"]);
    assert!(calibrated.status.success(), "{}", String::from_utf8_lossy(&calibrated.stderr));
    let calibrate_json: serde_json::Value = serde_json::from_slice(&calibrated.stdout).unwrap();
    let path = write_temp("calibrate.json", &String::from_utf8(calibrated.stdout).unwrap());
    let on_board = upload_then_download(&sim.path, &path);
    assert_eq!(on_board["model"], "ortho9");
    assert!(largest_difference(&on_board, &calibrate_json["calibration"]) < 1e-7);
    // download: the board's own record, uploaded again unchanged.
    let path = write_temp("download.json", &on_board.to_string());
    assert_eq!(upload_then_download(&sim.path, &path), on_board);
    // fit --json on data in g: six faces of a sensor with 20 mg offsets and 1 % scale errors.
    let faces = "x,y,z\n1.03,0.02,-0.02\n-0.99,0.02,-0.02\n0.02,1.01,-0.02\n0.02,-0.97,-0.02\n\
                 0.02,0.02,0.98\n0.02,0.02,-1.02\n";
    let fitted =
        accelcal(&["fit", write_temp("faces.csv", faces).to_str().unwrap(), "--model", "six-position", "--json"]);
    assert!(fitted.status.success(), "{}", String::from_utf8_lossy(&fitted.stderr));
    let fit_json: serde_json::Value = serde_json::from_slice(&fitted.stdout).unwrap();
    let on_board = upload_then_download(&sim.path, &write_temp("fit.json", &String::from_utf8(fitted.stdout).unwrap()));
    assert_eq!(on_board["model"], "six-position");
    assert!(largest_difference(&on_board, &fit_json) < 1e-7);
    assert!((on_board["offset"][0].as_f64().unwrap() - 0.02).abs() < 1e-6, "{on_board}");
}

#[test]
fn an_absurd_upload_is_refused_with_the_reason_before_it_reaches_the_board() {
    let path =
        write_temp("absurd.json", r#"{"model": "ortho9", "matrix": [[1,0,0],[0,1,0],[0,0,1]], "offset": [3.0, 0, 0]}"#);
    let output = accelcal(&["upload", "--sim", path.to_str().unwrap(), "--save"]);
    assert!(!output.status.success());
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert_eq!(stderr.trim_end(), "accelcal: refused before upload: the x offset 3.000 g is larger than 0.5 g");
    let fit_in_si = write_temp(
        "si.json",
        r#"{"model": "ortho9", "g": 9.81, "matrix": [[1,0,0],[0,1,0],[0,0,1]], "offset": [0, 0, 0]}"#,
    );
    let output = accelcal(&["upload", "--sim", fit_in_si.to_str().unwrap()]);
    assert!(String::from_utf8(output.stderr).unwrap().contains("this fit is not in g: fit data in g with --g 1"));
}

#[test]
fn calibrate_json_on_a_port_without_yes_is_refused_at_once_naming_the_missing_flag() {
    let sim = SimPty::with_seed("6", &[]);
    let mut child = Command::new(env!("CARGO_BIN_EXE_accelcal"))
        .args(["calibrate", "--port", &sim.path, "--json"])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // NOTE: without the refusal it waits for a person who never turns the board: give it 2 s.
    std::thread::sleep(std::time::Duration::from_secs(2));
    let finished = child.try_wait().unwrap();
    let _ = child.kill();
    let output = child.wait_with_output().unwrap();
    assert!(finished.is_some_and(|status| !status.success()), "still running or exit 0 after 2 s: {finished:?}");
    assert!(output.stdout.is_empty());
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert!(stderr.starts_with("accelcal: --json cannot ask") && stderr.contains("add --yes"), "{stderr}");
}

#[test]
fn every_out_of_range_argument_is_refused_when_parsed_naming_the_allowed_range() {
    let cases: [(&[&str], &str); 9] = [
        (&["calibrate", "--sim", "--target-mg", "0.01"], "not in 0.05-10 mg"),
        (&["calibrate", "--sim", "--seconds", "4"], "5..=20"),
        (&["calibrate", "--sim", "--seconds", "21"], "5..=20"),
        (&["capture", "--sim", "--session", "s", "--seconds", "0"], "5..=20"),
        (&["calibrate", "--sim", "--verify", "17"], "1..=16"),
        (&["verify", "--sim", "--positions", "17"], "1..=16"),
        (&["calibrate", "--sim", "--sim-placement-deg", "9"], "not in 0-8 degrees"),
        (&["stream", "--sim", "--rate", "30"], "does not divide the 100 Hz sample rate"),
        (&["stream", "--sim", "--rate", "0"], "does not divide the 100 Hz sample rate"),
    ];
    for (args, allowed) in cases {
        let started = std::time::Instant::now();
        let output = accelcal(args);
        let stderr = String::from_utf8(output.stderr).unwrap();
        assert_eq!(output.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains(allowed), "{args:?}: {stderr}");
        assert!(started.elapsed() < std::time::Duration::from_secs(2), "{args:?} refused only after it started");
    }
    let help = String::from_utf8(accelcal(&["calibrate", "--help"]).stdout).unwrap();
    assert!(help.contains("Seconds to average each position (5-20)") && help.contains("(1-16)"), "{help}");
    assert!(help.contains("(0-8)"), "{help}");
}

#[test]
fn calibrate_sim_with_one_seed_gives_the_same_calibration_every_run() {
    // NOTE: seed 10 misses the 0.2 mg target (exit 2) and still prints its result, without a
    // certificate.
    let run = |seed: &str| {
        let output = accelcal(&["calibrate", "--sim", "--seed", seed, "--json"]);
        assert!(output.status.success() || seed == "10", "{}", String::from_utf8_lossy(&output.stderr));
        without_the_wall_clock(serde_json::from_slice(&output.stdout).unwrap())
    };
    let first = run("9");
    for _ in 0..4 {
        assert_eq!(run("9"), first, "another result from the same seed");
    }
    assert_ne!(run("10"), first, "the seed makes no difference");
}

/// A `calibrate --json` result without what the wall clock decides: the certificate's date (UTC
/// minutes, which a run may cross) and so its hash.
fn without_the_wall_clock(mut result: serde_json::Value) -> serde_json::Value {
    if result["target"]["missed"] == true {
        assert!(result["certificate"].is_null(), "a calibration that missed its target has no certificate");
        return result;
    }
    let certificate = result["certificate"].as_object_mut().unwrap();
    for field in ["date_utc", "sha256"] {
        assert!(certificate.remove(field).is_some(), "no certificate.{field}");
    }
    assert!(certificate["board"].as_object_mut().unwrap().remove("date_utc").is_some(), "no board.date_utc");
    result
}

#[test]
fn a_resumed_session_goes_on_as_it_was_begun_and_says_which_flags_it_does_not_use() {
    let stem = std::env::temp_dir().join(format!("accelcal-cli-{}-resumed", std::process::id()));
    let session = stem.to_str().unwrap();
    let first = accelcal(&["calibrate", "--sim", "--seed", "4", "--session", session, "--yes", "--json"]);
    assert!(first.status.success(), "{}", String::from_utf8_lossy(&first.stderr));
    let json = stem.with_extension("json");
    let again = ["calibrate", "--sim", "--seed", "4", "--resume", json.to_str().unwrap(), "--yes"];
    let output = accelcal(&[&again[..], &["--seconds", "5", "--chip-fit"]].concat());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    assert!(stderr.contains("begun as a full calibration; it goes on as one (--chip-fit is not used"), "{stderr}");
    assert!(stderr.contains("begun adaptive") && stderr.contains("--seconds 5 is not used"), "{stderr}");
    // Thirteen positions and +Z again: the closing capture is no fourteenth position.
    assert!(stderr.contains("13 of 14 positions captured") && stderr.contains("13 positions predict"), "{stderr}");
    // Its moves were recorded in the first run only: the G that run fitted and uploaded is kept.
    assert!(stderr.contains("G kept from the calibration this session uploaded in an earlier run"), "{stderr}");
    let output = accelcal(&again);
    let (stdout, stderr) = (String::from_utf8_lossy(&output.stdout), String::from_utf8_lossy(&output.stderr));
    assert!(output.status.success() && !stderr.contains("is not used"), "{stderr}");
    // Its first capture was taken in the other run: the board's time is not known, not this run's.
    assert!(stdout.contains("verified at 3") && !stdout.contains("the board was kept"), "{stdout}");
    let output = accelcal(&[&again[..], &["--json"]].concat());
    let json_out: serde_json::Value = serde_json::from_slice(&output.stdout).expect("one JSON object");
    assert!(json_out["board_seconds"].is_null(), "{}", json_out["board_seconds"]);
    std::fs::remove_file(&json).unwrap();
}

#[test]
fn a_resumed_chip_fit_session_says_it_stays_so_and_a_fixed_length_one_is_not_called_adaptive() {
    let resumed = |begun: &[&str], again: &[&str], name: &str| {
        let stem = std::env::temp_dir().join(format!("accelcal-cli-{}-{name}", std::process::id()));
        let session = stem.to_str().unwrap();
        let first = accelcal(&[&["calibrate", "--sim", "--seed", "4", "--session", session, "--yes"], begun].concat());
        assert!(first.status.success(), "{}", String::from_utf8_lossy(&first.stderr));
        let json = stem.with_extension("json");
        let resume = ["calibrate", "--sim", "--seed", "4", "--resume", json.to_str().unwrap(), "--yes"];
        let output = accelcal(&[&resume[..], again].concat());
        std::fs::remove_file(&json).unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
        assert!(output.status.success(), "{stderr}");
        stderr
    };
    let quick = resumed(&["--chip-fit"], &[], "quick");
    assert!(
        quick.contains(
            "begun as a calibration fitted on the chip; it goes on as one (leaving out --chip-fit is not used"
        ),
        "{quick}"
    );
    // A fixed-length session was not begun adaptive: its --seconds is not refused in those words.
    let fixed = resumed(&["--seconds", "5"], &["--seconds", "6"], "fixed");
    assert!(!fixed.contains("begun adaptive") && !fixed.contains("is not used"), "{fixed}");
}

#[test]
fn a_reader_that_goes_away_ends_the_command_quietly_with_the_closed_pipe_s_status() {
    // NOTE: the pipe's reading end is closed before the command starts, so its first print fails
    // (as `accelcal fit FILE | head -0` would), whatever the timing.
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    let output = Command::new(env!("CARGO_BIN_EXE_accelcal"))
        .args(["fit", &phone_data(), "--g", "9.81"])
        .stdout(writer)
        .output()
        .expect("accelcal runs");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(accelcal::terminal::READER_GONE_EXIT), "{stderr}");
    assert!(stderr.is_empty(), "nothing said when nobody reads: {stderr}");
}

/// The numbers of the C header's `static const float NAME[...] = {...};` line, in order.
fn c_floats(header: &str, name: &str) -> Vec<f64> {
    let line =
        header.lines().find(|l| l.contains(&format!(" {name}["))).unwrap_or_else(|| panic!("{name} in {header}"));
    let values = &line[line.find('=').unwrap() + 1..line.rfind(';').unwrap()];
    values.split(',').map(|v| v.trim_matches(|c: char| " {}f".contains(c)).parse().unwrap()).collect()
}

#[test]
fn a_sketch_s_fit_exports_in_g_with_its_own_gyro_counts_its_turns_g_and_no_invented_temperature() {
    let log = write_temp("sketch.log", "");
    let printed = accelcal(&["sim", "--sketch", "csv", "--seed", "3"]);
    std::fs::write(&log, &printed.stdout).unwrap();
    let fitted = accelcal(&["fit", log.to_str().unwrap(), "--json"]);
    assert!(fitted.status.success(), "{}", String::from_utf8_lossy(&fitted.stderr));
    let fit: serde_json::Value = serde_json::from_slice(&fitted.stdout).unwrap();
    assert_eq!((fit["input_unit"].as_str(), fit["gyro_unit"].as_str()), (Some("counts-2g"), Some("counts-250dps")));
    let json = write_temp("sketch-fit.json", &String::from_utf8(fitted.stdout).unwrap());
    let exported = accelcal(&["export", json.to_str().unwrap(), "--to", "c"]);
    let header = String::from_utf8_lossy(&exported.stdout);
    assert!(exported.status.success(), "{}", String::from_utf8_lossy(&exported.stderr));
    // NOTE: the fit's M takes counts (16384 a g at +-2 g): in g it is 16384 times larger, its o
    // 16384 times smaller; the gyro's counts are 131 a deg/s at +-250 deg/s (Product Specification 6.1-6.2).
    let flat = |v: &serde_json::Value| -> Vec<f64> {
        v.as_array()
            .unwrap()
            .iter()
            .flat_map(|x| x.as_array().cloned().unwrap_or(vec![x.clone()]))
            .map(|x| x.as_f64().unwrap())
            .collect()
    };
    let close = |ours: &[f64], theirs: Vec<f64>, scale: f64, what: &str| {
        for (a, b) in ours.iter().zip(&theirs) {
            assert!(
                (a - b * scale).abs() <= 1e-6 * (b * scale).abs().max(1e-3),
                "{what}: {ours:?} against {theirs:?} x {scale}"
            );
        }
    };
    close(&c_floats(&header, "accelcal_accel_matrix"), flat(&fit["matrix"]), 16384.0, "M");
    close(&c_floats(&header, "accelcal_accel_offset_g"), flat(&fit["offset"]), 1.0 / 16384.0, "o");
    close(&c_floats(&header, "accelcal_gyro_matrix"), flat(&fit["gyro_fit"]["matrix"]), 1.0, "G");
    assert!(header.contains("#define ACCELCAL_GYRO_LSB_PER_DPS 131.0f"), "{header}");
    assert!(header.contains("made at: die temperature not measured"), "{header}");
}

#[test]
fn a_simulator_s_setting_given_with_a_real_port_is_refused_before_the_port_is_opened() {
    for setting in
        [&["--seed", "3"][..], &["--sim-sensor", "settled"], &["--sim-part", "mpu6500"], &["--sim-faulty-axis", "x"]]
    {
        let args = [&["info", "--port", "/dev/accelcal-no-such-port"][..], setting].concat();
        let output = accelcal(&args);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{setting:?}: {stderr}");
        assert!(stderr.contains(setting[0]) && stderr.contains("cannot be used with"), "{setting:?}: {stderr}");
        assert!(!stderr.contains("no-such-port"), "{setting:?}: the port was tried first: {stderr}");
    }
}

#[test]
fn a_first_simulated_run_says_it_was_simulated_that_nothing_was_kept_and_what_to_run_next() {
    let output = accelcal(&["calibrate", "--sim", "--yes", "--seed", "2"]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    assert!(stderr.contains("this was a simulated board") && stderr.contains("nothing was kept"), "{stderr}");
    assert!(stderr.contains("next: with your board plugged in, `accelcal calibrate --port PORT`"), "{stderr}");
    let stem = std::env::temp_dir().join(format!("accelcal-cli-{}-first-kept", std::process::id()));
    let kept = accelcal(&["calibrate", "--sim", "--yes", "--seed", "2", "--session", stem.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&kept.stderr);
    assert!(kept.status.success() && !stderr.contains("nothing was kept"), "{stderr}");
}

/// Issue 40: the figure stated for a fresh orientation ignored the model's misfit (on a real
/// 160-position recording it promised 0.29 mg while the rows left out one at a time showed 1.09 mg).
/// On Ivanov et al.'s 32 fixture positions, whose rows carry no noise, the rows left out show
/// 8.859 mg against the parameters' 3.621 mg: the stated figure is now the held-out one.
#[test]
fn the_figure_at_a_fresh_orientation_holds_the_misfit_the_rows_left_out_show() {
    let data = format!("{}/../tests/data/ivanov-lab-32.csv", env!("CARGO_MANIFEST_DIR"));
    let output = accelcal(&["fit", &data, "--json"]);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    let model = json["model"].as_str().unwrap();
    let scores = json["selection"]["leave_one_out"].as_array().unwrap();
    let held_out = scores.iter().find(|s| s[0] == model).and_then(|s| s[1].as_f64()).expect("the model's figure");
    let g = json["g"].as_f64().unwrap();
    let (held_out_mg, prediction) = (held_out / g * 1000.0, &json["prediction"]);
    let stated = prediction["norm_error_mg"].as_f64().unwrap();
    assert!((stated - held_out_mg).abs() < 1e-9 * held_out_mg, "stated {stated} mg, held out {held_out_mg} mg");
    let misfit = prediction["misfit_mg"].as_f64().unwrap();
    assert!(misfit > 0.5 * stated, "misfit {misfit} mg of {stated} mg");
    let text = String::from_utf8(accelcal(&["fit", &data]).stdout).unwrap();
    assert!(text.contains(&format!("expect | |a| - g | of {stated:.4} mg")), "{text}");
    assert!(text.contains("of misfit beyond it"), "{text}");
}
