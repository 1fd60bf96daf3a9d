//! `accelcal record`: every sample at 1 kHz into a `.npy` recording that numpy and our reader load,
//! also after the link is cut mid-recording; `noise` reads it as it reads the stream's CSV.

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Duration;

use accelcal::recording::read_path;
use common::{accelcal_within, SimPty};

fn temp(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("accelcal-record-{}-{name}", std::process::id()))
}

fn record_sim(seconds: &str, path: &Path) {
    let args = ["record", "--sim", "--rate", "1000", "--seconds", seconds, "-o", path.to_str().unwrap()];
    let (output, _) = accelcal_within(&args, Duration::from_secs(300));
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
}

#[test]
fn a_60_s_sim_recording_at_1_khz_holds_60000_consecutive_samples_1_ms_apart() {
    let path = temp("60s.npy");
    record_sim("60", &path);
    let recording = read_path(&path).unwrap();
    let samples = recording.samples;
    assert_eq!((samples.len(), recording.rate_hz), (60_000, 1000));
    for (i, sample) in samples.iter().enumerate() {
        assert_eq!((sample.index, sample.time_us), (i as u32, i as u64 * 1000), "sample {i}");
    }
    // The realistic sensor lies flat: z near 1 g, die temperature near room temperature.
    let last = samples.last().unwrap();
    assert!((last.accel_g[2] - 1.0).abs() < 0.1 && (15.0..40.0).contains(&last.temp_c), "{last:?}");
    let header = accelcal::recording::header::HEADER_BYTES as u64;
    assert_eq!(std::fs::metadata(&path).unwrap().len(), header + 60_000 * 32, "32 bytes per sample");
    assert_eq!(recording.serial.as_deref(), Some("53494D000000000000000001"), "the simulated board of seed 1");
    std::fs::remove_file(path).unwrap();
}

/// The same samples as `path` holds, as CSV with the stream's columns, every digit kept.
fn as_csv(path: &Path) -> PathBuf {
    let mut text = String::from("index,time_s,ax_g,ay_g,az_g,gx_dps,gy_dps,gz_dps,temp_c,board\n");
    let recording = read_path(path).unwrap();
    let board = recording.serial.unwrap();
    for s in recording.samples {
        // NOTE: as f64, whose shortest decimal reads back to the very value the recording's f32 gives.
        let ([ax, ay, az], [gx, gy, gz]) = (s.accel_g.map(f64::from), s.gyro_dps.map(f64::from));
        text +=
            &format!("{},{},{ax},{ay},{az},{gx},{gy},{gz},{},{board}\n", s.index, s.time_us as f64 * 1e-6, s.temp_c);
    }
    let csv = path.with_extension("csv");
    std::fs::write(&csv, text).unwrap();
    csv
}

#[test]
fn noise_on_a_recording_gives_the_same_report_as_on_the_equivalent_csv() {
    let path = temp("noise.npy");
    record_sim("20", &path);
    let csv = as_csv(&path);
    let noise = |file: &Path| accelcal_within(&["noise", file.to_str().unwrap(), "--json"], Duration::from_secs(60)).0;
    let (from_npy, from_csv) = (noise(&path), noise(&csv));
    assert!(from_npy.status.success(), "{}", String::from_utf8_lossy(&from_npy.stderr));
    let json: serde_json::Value = serde_json::from_slice(&from_npy.stdout).unwrap();
    assert!(json["accel_z"]["white_noise_density"].as_f64().unwrap() > 0.0, "{json}");
    assert!(
        from_npy.stdout == from_csv.stdout,
        "the reports differ; from the CSV: {}",
        String::from_utf8_lossy(&from_csv.stdout)
    );
    std::fs::remove_file(path).unwrap();
    std::fs::remove_file(csv).unwrap();
}

/// The simulated sensor's true white noise densities (as its datasheet states them, one-sided).
const TRUE_DENSITY: [f32; 2] =
    [firmware::sim::physics::ACCEL_NOISE_DENSITY_G * 1e6, firmware::sim::physics::GYRO_NOISE_DENSITY_DPS];

#[test]
fn noise_finds_the_simulated_sensors_white_noise_within_5_percent_in_a_60_s_recording_at_1_khz() {
    let path = temp("density.npy");
    record_sim("60", &path);
    let output = accelcal_within(&["noise", path.to_str().unwrap(), "--json"], Duration::from_secs(60)).0;
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    for (k, axis) in ["accel_x", "accel_y", "accel_z", "gyro_x", "gyro_y", "gyro_z"].iter().enumerate() {
        let truth = f64::from(TRUE_DENSITY[k / 3]);
        let ratio = json[axis]["white_noise_density"].as_f64().unwrap() / truth;
        eprintln!("{axis}: white noise density {ratio:.4} x the truth");
        assert!((ratio - 1.0).abs() < 0.05, "{axis}: {ratio} x the simulated sensor's {truth}");
    }
    std::fs::remove_file(path).unwrap();
}

#[test]
fn noise_takes_the_rate_from_the_recording_and_refuses_another() {
    let path = temp("100hz.npy");
    let args = ["record", "--sim", "--rate", "100", "--seconds", "30", "-o", path.to_str().unwrap()];
    assert!(accelcal_within(&args, Duration::from_secs(120)).0.status.success());
    let output = accelcal_within(&["noise", path.to_str().unwrap(), "--json"], Duration::from_secs(60)).0;
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    assert_eq!((json["sample_rate_hz"].as_f64(), json["samples"].as_u64()), (Some(100.0), Some(3000)));
    let output = accelcal_within(&["noise", path.to_str().unwrap(), "--rate", "1000"], Duration::from_secs(60)).0;
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        !output.status.success() && stderr.contains("differs from the 100 Hz the recording was taken at"),
        "{stderr}"
    );
    std::fs::remove_file(path).unwrap();
}

/// Python with numpy; the test that needs it is ignored where the build found none (and CI is not set).
fn numpy() {
    let found = Command::new("python3").args(["-c", "import numpy"]).status().is_ok_and(|s| s.success());
    assert!(found, "python3 with numpy is not installed (pip install numpy)");
}

#[test]
#[cfg_attr(not(has_numpy), ignore = "needs python3 with numpy (pip install numpy); CI=true runs it")]
fn the_readme_python_one_liner_loads_a_recording_with_its_columns() {
    numpy();
    let path = temp("python.npy");
    record_sim("3", &path);
    // The rate rides in the title of the `seq` field: the sample time is seq / rate.
    let script = "import numpy as np, sys; r = np.load(sys.argv[1]); \
                  print(len(r), int((r['seq'] == np.arange(len(r))).all()), round(float(r['az_g'].mean())), \
                  r.dtype.fields['seq'][2])";
    let output = Command::new("python3").args(["-c", script, path.to_str().unwrap()]).output().unwrap();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let expected =
        "3000 1 1 sample number; samples per second: 1000; board 53494D000000000000000001; time_s = seq / 1000";
    assert_eq!(String::from_utf8_lossy(&output.stdout).trim(), expected);
    std::fs::remove_file(path).unwrap();
}

/// A recording over `accelcal sim --pty` cut after 20 000 samples are on disk by `cut`: the command
/// fails naming `cause`, and the file holds every sample up to the cut, as many as the message says.
fn cut_recording(name: &str, cut: impl FnOnce(SimPty, &std::process::Child), cause: &str) {
    let sim = SimPty::start(&["--fast"]);
    let path = temp(name);
    let mut record = Command::new(env!("CARGO_BIN_EXE_accelcal"))
        .args(["record", "--port", &sim.path, "--rate", "1000", "--seconds", "3600", "-o", path.to_str().unwrap()])
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let on_disk = wait_for_samples(&path, 20_000);
    cut(sim, &record);
    let status = common::wait_or_kill(&mut record, Duration::from_secs(20));
    let mut stderr = String::new();
    std::io::Read::read_to_string(&mut record.stderr.take().unwrap(), &mut stderr).unwrap();
    assert!(!status.success(), "a cut recording must fail: {stderr}");
    assert!(stderr.contains(cause) && stderr.contains("are kept in") && stderr.contains("np.load"), "{stderr}");
    let samples = read_path(&path).unwrap().samples;
    assert!(samples.len() >= on_disk, "{} samples read, {on_disk} were on disk before the cut", samples.len());
    assert!(samples.iter().enumerate().all(|(i, s)| s.index == i as u32), "a sample before the cut is missing");
    assert!(stderr.contains(&format!("the {} samples", samples.len())), "{stderr}");
    // NOTE: the cut itself is tested everywhere; np.load's reading of it where numpy is (see numpy()).
    if cfg!(has_numpy) {
        numpy();
        assert_eq!(numpy_count(&path), samples.len(), "np.load reads another count");
    }
    std::fs::remove_file(path).unwrap();
}

/// How many records `np.load` reads from the recording at `path`.
fn numpy_count(path: &Path) -> usize {
    let script = "import numpy as np, sys; print(len(np.load(sys.argv[1])))";
    let output = Command::new("python3").args(["-c", script, path.to_str().unwrap()]).output().unwrap();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    String::from_utf8_lossy(&output.stdout).trim().parse().unwrap()
}

#[test]
fn a_pulled_cable_leaves_a_readable_file_with_every_sample_up_to_the_cut() {
    // The board's end of the link is gone.
    cut_recording("cut.npy", |sim, _| drop(sim), "the device");
}

#[test]
fn ctrl_c_leaves_a_readable_file_with_every_sample_up_to_it_and_says_how_many() {
    let interrupt = |sim: SimPty, record: &std::process::Child| {
        let status = Command::new("kill").args(["-INT", &record.id().to_string()]).status().unwrap();
        assert!(status.success());
        // The board stays plugged in until the command has ended.
        std::thread::sleep(Duration::from_secs(2));
        drop(sim);
    };
    cut_recording("ctrl-c.npy", interrupt, "interrupted (Ctrl-C)");
}

/// Waits until the recording at `path` holds at least `samples` complete records; how many it holds.
fn wait_for_samples(path: &Path, samples: usize) -> usize {
    for _ in 0..1500 {
        let held = std::fs::metadata(path).map_or(0, |m| (m.len() as usize).saturating_sub(320) / 32);
        if held >= samples {
            return held;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    panic!("the recording never reached {samples} samples");
}

#[test]
fn samples_lost_on_the_link_are_counted_and_fail_the_recording_which_keeps_the_rest() {
    let mut sim = SimPty::start(&["--fast"]);
    sim.command("lose 7");
    let path = temp("lost.npy");
    let args = ["record", "--port", &sim.path, "--rate", "1000", "--seconds", "2", "-o", path.to_str().unwrap()];
    let (output, _) = accelcal_within(&args, Duration::from_secs(60));
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert!(!output.status.success(), "{stderr}");
    assert!(stderr.contains("7 of 2000 samples were lost") && stderr.contains("7 on the link"), "{stderr}");
    let samples = read_path(&path).unwrap().samples;
    assert_eq!(samples.len(), 1993);
    assert_eq!(samples[0].index, 7, "the link lost the first 7");
    std::fs::remove_file(path).unwrap();
}
