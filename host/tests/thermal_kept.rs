//! `accelcal thermal --port` keeps its learned bins on disk as it learns: Ctrl-C fits what it
//! learned when that spans enough, else names the file, and a second run goes on from it; a pulled
//! cable leaves the bins on disk, named with the way to go on.

mod common;

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

use common::SimPty;

fn accelcal(args: &[&str]) -> Output {
    common::accelcal_within(args, Duration::from_secs(60)).0
}

fn temp_path(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("accelcal-thermal-kept-{}-{name}", std::process::id()))
}

/// A simulated board on a pseudo-terminal with a calibration active (thermal learns around it).
fn calibrated_board(seed: &str) -> SimPty {
    let sim = SimPty::with_seed(seed, &["--fast"]);
    let file = temp_path(&format!("calibration-{seed}.json"));
    let calibration = accelcal(&["calibrate", "--sim", "--chip-fit", "--yes", "--json"]);
    std::fs::write(&file, calibration.stdout).unwrap();
    assert!(accelcal(&["upload", "--port", &sim.path, file.to_str().unwrap()]).status.success());
    sim
}

fn thermal(port: &str, bins: &Path) -> Child {
    Command::new(env!("CARGO_BIN_EXE_accelcal"))
        .args(["thermal", "--port", port, "--bins", bins.to_str().unwrap()])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap()
}

/// The kept bins' span in degC once the file shows at least `span_c` (waits up to `limit`).
fn kept_span_reaches(bins: &Path, span_c: f64, limit: Duration) -> f64 {
    let started = Instant::now();
    loop {
        let span = std::fs::read(bins).ok().and_then(|bytes| serde_json::from_slice::<serde_json::Value>(&bytes).ok());
        let span = span.map_or(-1.0, |json| {
            json["range_c"][1].as_f64().unwrap_or(0.0) - json["range_c"][0].as_f64().unwrap_or(0.0)
        });
        if span >= span_c || started.elapsed() > limit {
            return span;
        }
        std::thread::sleep(Duration::from_millis(200));
    }
}

fn ctrl_c(child: Child) -> Output {
    let status = Command::new("kill").args(["-INT", &child.id().to_string()]).status().unwrap();
    assert!(status.success());
    let mut child = child;
    common::wait_or_kill(&mut child, Duration::from_secs(20));
    child.wait_with_output().unwrap()
}

#[test]
fn ctrl_c_under_ten_degc_keeps_the_bins_on_disk_and_a_second_run_goes_on_from_them() {
    let sim = calibrated_board("31");
    let bins = temp_path("short.json");
    let first = thermal(&sim.path, &bins);
    assert!(kept_span_reaches(&bins, 0.0, Duration::from_secs(30)) >= 0.0, "no bins were kept");
    let output = ctrl_c(first);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success(), "{stderr}");
    assert!(
        stderr.contains("interrupted (Ctrl-C)") && stderr.contains("the bins learned so far (a span of"),
        "{stderr}"
    );
    assert!(stderr.contains(&format!("--bins {}", bins.display())), "{stderr}");
    let second = thermal(&sim.path, &bins);
    std::thread::sleep(Duration::from_secs(2));
    let stderr = String::from_utf8_lossy(&ctrl_c(second).stderr).into_owned();
    assert!(stderr.contains("going on from the 1 bins"), "{stderr}");
}

#[test]
// NOTE: once intermittent: a quick 16 degC warming's cubic left the plausible offset drift over -40..85 degC and
// the fit was refused; the order is now limited by the span learned (limits::THERMAL_SPAN_PER_ORDER_C).
fn ctrl_c_after_ten_degc_fits_and_activates_what_was_learned() {
    let mut sim = calibrated_board("32");
    let bins = temp_path("warming.json");
    let run = thermal(&sim.path, &bins);
    // The board is carried into a hot place: its die warms by tens of degrees over minutes.
    sim.tell("ambient 85");
    // NOTE: 16 degC: a fit needs 10 degC and at least 6 bins, which the quick first warming can lack.
    let span = kept_span_reaches(&bins, 16.0, Duration::from_secs(150));
    assert!(span >= 16.0, "the kept bins span {span} degC");
    let output = ctrl_c(run);
    let (stdout, stderr) = (String::from_utf8_lossy(&output.stdout), String::from_utf8_lossy(&output.stderr));
    assert!(output.status.success(), "{stderr}");
    assert!(stdout.contains("interrupted") && stdout.contains("fitted what was learned"), "{stdout}");
    let active = String::from_utf8(accelcal(&["download", "--port", &sim.path]).stdout).unwrap();
    assert!(active.contains("\"temperature\""), "the fitted model is not active: {active}");
}

#[test]
fn a_pulled_cable_keeps_the_bins_on_disk_and_names_them_with_the_way_to_go_on() {
    let sim = calibrated_board("33");
    let bins = temp_path("pulled.json");
    let mut run = thermal(&sim.path, &bins);
    assert!(kept_span_reaches(&bins, 0.0, Duration::from_secs(30)) >= 0.0, "no bins were kept");
    let port = sim.path.clone();
    drop(sim);
    common::wait_or_kill(&mut run, Duration::from_secs(30));
    let output = run.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success(), "{stderr}");
    let way_on = format!("are kept in {}: go on from them with `accelcal thermal --port {port} --bins", bins.display());
    assert!(stderr.contains("the bins learned so far (a span of") && stderr.contains(&way_on), "{stderr}");
    let kept: serde_json::Value = serde_json::from_slice(&std::fs::read(&bins).unwrap()).unwrap();
    assert!(!kept["bins"].as_array().unwrap().is_empty(), "{kept}");
    std::fs::remove_file(bins).unwrap();
}
