//! The factory's formats (issue 41): three boards' certificates exported from a lot as OpenHTF JSON
//! test records and as OCP Test & Validation artifacts, read back by the formats' own tools
//! (host/tests/records/*.py: openhtf's classes and the ocptv package's writer rebuild each record and
//! must give it field for field), with their units, the spec's limits as validators and each
//! parameter's expanded uncertainty beside it.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Duration;

use accelcal::certificate::Certificate;
use common::accelcal_within;

const LIMIT: Duration = Duration::from_secs(120);

/// Three boards' certificates and a spec whose o_x high limit lies between the two largest o_x, so
/// exactly one board fails; its (low, high), and the folder they were written to.
fn lot_of_three(name: &str) -> (PathBuf, Vec<Certificate>, (f64, f64)) {
    let dir = std::env::temp_dir().join(format!("accelcal-records-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let certificates: Vec<Certificate> = (1..=3)
        .map(|seed| {
            let mut c = Certificate::issue(&accelcal::sim::sessions::adaptive(seed, 1.0, 2.8e-3)).unwrap();
            c.board.serial = Some(format!("B{seed}"));
            c.date_utc = Some(format!("2026-11-2{seed} 10:00"));
            c.resealed()
        })
        .collect();
    let mut values: Vec<f64> = certificates.iter().map(|c| c.parameters["o_x"].value).collect();
    values.sort_by(f64::total_cmp);
    let limits = (values[0] - 0.01, (values[1] + values[2]) / 2.0);
    std::fs::write(dir.join("spec.toml"), format!("[limits.o_x]\nlow = {:?}\nhigh = {:?}\n", limits.0, limits.1))
        .unwrap();
    std::fs::write(dir.join("spec.json"), format!("{{\"o_x\": [{:?}, {:?}]}}", limits.0, limits.1)).unwrap();
    let files: Vec<String> = certificates
        .iter()
        .map(|c| {
            let file = dir.join(format!("{}.certificate.json", c.board.serial.as_deref().unwrap()));
            std::fs::write(&file, c.to_json()).unwrap();
            file.to_string_lossy().into_owned()
        })
        .collect();
    let lot = dir.join("lot.sqlite").to_string_lossy().into_owned();
    let mut add = vec!["lot", "add", &lot, "--station", "st-4"];
    add.extend(files.iter().map(String::as_str));
    assert!(accelcal_within(&add, LIMIT).0.status.success());
    (dir, certificates, limits)
}

/// `accelcal lot export` into `dir/FORMAT`, then the format's reader on every file; one summary per record.
fn exported_and_read(dir: &Path, format: &str, reader: &str) -> Vec<serde_json::Value> {
    let (lot, out, spec) = (dir.join("lot.sqlite"), dir.join(format), dir.join("spec.toml"));
    let args = ["lot", "export", lot.to_str().unwrap(), "--format", format, "--out", out.to_str().unwrap()];
    let (output, _) = accelcal_within(&[&args[..], &["--spec", spec.to_str().unwrap()]].concat(), LIMIT);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let mut files: Vec<PathBuf> = std::fs::read_dir(&out).unwrap().map(|e| e.unwrap().path()).collect();
    files.sort();
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/records").join(reader);
    let read = Command::new("python3").arg(script).arg(dir.join("spec.json")).args(&files).output().unwrap();
    assert!(read.status.success(), "{reader}: {}", String::from_utf8_lossy(&read.stderr));
    String::from_utf8_lossy(&read.stdout).lines().map(|l| serde_json::from_str(l).unwrap()).collect()
}

/// Each summary states its board, station and outcome, o_x with its unit and limits, and o_x_U.
fn check(summaries: &[serde_json::Value], certificates: &[Certificate], limits: (f64, f64), unit: &str) {
    assert_eq!(summaries.len(), 3);
    let failing = certificates.iter().map(|c| c.parameters["o_x"].value).fold(f64::MIN, f64::max);
    for (summary, certificate) in summaries.iter().zip(certificates) {
        let o_x = &certificate.parameters["o_x"];
        assert_eq!(summary["dut_id"], certificate.board.serial.as_deref().unwrap());
        assert_eq!(summary["station_id"], "st-4");
        assert_eq!(summary["outcome"], if o_x.value == failing { "FAIL" } else { "PASS" }, "{summary}");
        let read = &summary["fit"]["o_x"];
        assert!((read[0].as_f64().unwrap() - o_x.value).abs() <= 1e-15, "{read}");
        assert_eq!(read[1], unit);
        let read_u = &summary["fit"]["o_x_U"];
        assert!((read_u[0].as_f64().unwrap() - o_x.expanded).abs() <= 1e-15 && o_x.expanded > 0.0, "{read_u}");
        assert_eq!(read_u[2].as_array().unwrap().len(), 0, "an uncertainty has no limits: {read_u}");
        let validators = read[2].to_string();
        for limit in [limits.0, limits.1] {
            assert!(validators.contains(&format!("{limit:?}")), "{validators} lacks {limit}");
        }
    }
}

#[test]
#[cfg_attr(not(has_openhtf), ignore = "needs OpenHTF (pip install openhtf); CI=true runs it")]
fn three_boards_as_openhtf_test_records_read_back_by_openhtf_with_units_limits_and_uncertainties() {
    let (dir, certificates, limits) = lot_of_three("openhtf");
    let summaries = exported_and_read(&dir, "openhtf", "openhtf_reads.py");
    check(&summaries, &certificates, limits, "gn");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
#[cfg_attr(not(has_ocptv), ignore = "needs the OCP Test & Validation package (pip install ocptv); CI=true runs it")]
fn three_boards_as_ocp_artifacts_read_back_by_ocptv_with_units_limits_and_uncertainties() {
    let (dir, certificates, limits) = lot_of_three("ocp");
    let summaries = exported_and_read(&dir, "ocp", "ocp_reads.py");
    check(&summaries, &certificates, limits, "g");
    std::fs::remove_dir_all(&dir).unwrap();
}
