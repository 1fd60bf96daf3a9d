//! `accelcal stream` over `accelcal sim --pty`: every sample arrives, or the loss is counted and
//! named; a reader that goes away ends the stream.

mod common;

use std::io::{BufRead, BufReader};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use common::{accelcal_within, SimPty};

/// The sequence numbers (first CSV column) of the rows `accelcal stream` printed.
fn indices(stdout: &[u8]) -> Vec<u32> {
    let text = String::from_utf8(stdout.to_vec()).unwrap();
    text.lines().skip(1).map(|l| l.split(',').next().unwrap().parse().unwrap()).collect()
}

#[test]
fn a_stream_of_1000_samples_over_sim_pty_arrives_whole_with_consecutive_sequence_numbers() {
    let sim = SimPty::start(&["--fast"]);
    let args = ["stream", "--port", &sim.path, "--count", "1000", "--rate", "100"];
    let (output, elapsed) = accelcal_within(&args, Duration::from_secs(60));
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let indices = indices(&output.stdout);
    assert_eq!(indices.len(), 1000);
    // NOTE: --fast: 10 s of samples in a fraction of that (a bound, not a timing measurement).
    assert!(elapsed < Duration::from_secs(5), "took {elapsed:?}");
    assert!(indices.iter().enumerate().all(|(k, &i)| i == k as u32), "gaps in {indices:?}");
}

#[test]
fn samples_lost_on_the_link_are_counted_and_fail_the_command() {
    let mut sim = SimPty::start(&["--fast"]);
    sim.command("lose 7");
    let args = ["stream", "--port", &sim.path, "--count", "200", "--rate", "100"];
    let (output, _) = accelcal_within(&args, Duration::from_secs(60));
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert!(!output.status.success(), "{stderr}");
    assert!(stderr.starts_with("accelcal: 7 of 200 samples were lost (0 dropped by the board"), "{stderr}");
    assert!(stderr.contains("7 on the link"), "{stderr}");
    let indices = indices(&output.stdout);
    assert_eq!(indices.len(), 193);
    assert_eq!(indices[..3], [7, 8, 9], "the link lost the first 7");
}

#[test]
fn a_stream_into_head_ends_promptly_and_quietly_when_head_exits() {
    // Real time: 100 000 samples at 100 Hz would take 17 minutes.
    let sim = SimPty::start(&[]);
    let started = Instant::now();
    let mut child = Command::new(env!("CARGO_BIN_EXE_accelcal"))
        .args(["stream", "--port", &sim.path, "--count", "100000", "--rate", "100"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut lines = BufReader::new(child.stdout.take().unwrap()).lines();
    let head: Vec<String> = lines.by_ref().take(5).map(Result::unwrap).collect();
    assert!(head[0].starts_with("index,time_s,"), "{head:?}");
    drop(lines); // head exits
    let status = common::wait_or_kill(&mut child, Duration::from_secs(10));
    let mut stderr = String::new();
    std::io::Read::read_to_string(&mut child.stderr.take().unwrap(), &mut stderr).unwrap();
    assert!(status.success(), "{stderr}");
    assert_eq!(stderr, "");
    // NOTE: a bound on a hang: start-up, four samples at 100 Hz, the cancel's round trip.
    assert!(started.elapsed() < Duration::from_secs(3), "took {:?}", started.elapsed());
}

#[test]
fn sim_pty_runs_in_real_time_by_default() {
    let sim = SimPty::start(&[]);
    let args = ["stream", "--port", &sim.path, "--count", "60", "--rate", "100"];
    let (output, elapsed) = accelcal_within(&args, Duration::from_secs(30));
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    assert_eq!(indices(&output.stdout).len(), 60);
    // 60 samples at 100 Hz take 0.6 s of the sensor's time, and as long on the wall clock.
    assert!(elapsed >= Duration::from_millis(550), "took only {elapsed:?}: not real time");
    let last = String::from_utf8(output.stdout).unwrap().lines().last().unwrap().to_owned();
    assert!(last.starts_with("59,0.590000,"), "{last}");
}

#[test]
fn a_count_of_zero_is_refused_when_parsed_with_the_range() {
    let (output, _) = accelcal_within(&["stream", "--sim", "--count", "0"], Duration::from_secs(10));
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert!(!output.status.success());
    assert!(stderr.contains("invalid value '0' for '--count <COUNT>'"), "{stderr}");
    assert!(stderr.contains("1.."), "{stderr}");
}

#[test]
fn a_calibrated_stream_from_a_board_without_a_calibration_is_refused_and_streams_once_one_is_uploaded() {
    let sim = SimPty::start(&["--fast"]);
    let args = ["stream", "--port", &sim.path, "--count", "20", "--rate", "100", "--calibrated"];
    let (output, _) = accelcal_within(&args, Duration::from_secs(60));
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert!(!output.status.success(), "{stderr}");
    assert!(stderr.contains("no active calibration, so --calibrated would print its raw readings"), "{stderr}");
    assert!(output.stdout.is_empty(), "nothing streamed");
    let file = std::env::temp_dir().join(format!("accelcal-stream-{}-offset.json", std::process::id()));
    let offset = r#"{"model": "ortho9", "matrix": [[1,0,0],[0,1,0],[0,0,1]], "offset": [0.25, 0, 0], "g": 1.0}"#;
    std::fs::write(&file, offset).unwrap();
    let (uploaded, _) =
        accelcal_within(&["upload", "--port", &sim.path, file.to_str().unwrap()], Duration::from_secs(60));
    assert!(uploaded.status.success(), "{}", String::from_utf8_lossy(&uploaded.stderr));
    let (output, _) = accelcal_within(&args, Duration::from_secs(60));
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    assert_eq!(indices(&output.stdout).len(), 20);
}
