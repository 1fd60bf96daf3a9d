//! What the export tests share: one simulated calibration (with the simulated sensor's truth), the
//! exports of it, raw readings, accelcal's own correction written out here from the JSON, and the
//! external tools they need.

#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

/// The standard gravity the tests convert with, written here independently of the exporter.
pub const G: f64 = 9.80665;

/// A 3x3 matrix, rows.
pub type Mat = [[f64; 3]; 3];

/// The simulated calibration: its JSON file and the values read from it.
pub struct Simulated {
    pub dir: PathBuf,
    pub json: PathBuf,
    pub matrix: Mat,
    pub offset: [f64; 3],
    pub gyro_matrix: Mat,
    pub gyro_bias: [f64; 3],
    pub true_matrix: Mat,
    pub true_offset: [f64; 3],
    pub true_gyro_matrix: Mat,
    pub true_gyro_bias: [f64; 3],
}

/// `calibrate --sim --sim-sensor settled --yes --json`, once per test binary: the settled sensor holds its
/// true errors (the JSON's `truth`) at every temperature, so the truth is what every capture saw.
pub fn simulated() -> &'static Simulated {
    static ONCE: OnceLock<Simulated> = OnceLock::new();
    ONCE.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("accelcal-export-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let output = accelcal(&["calibrate", "--sim", "--sim-sensor", "settled", "--yes", "--json"]);
        assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
        let json = dir.join("cal.json");
        std::fs::write(&json, &output.stdout).unwrap();
        let value: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
        let (cal, truth) = (&value["calibration"], &value["truth"]);
        Simulated {
            dir,
            json,
            matrix: matrix(&cal["matrix"]),
            offset: vector(&cal["offset"]),
            gyro_matrix: matrix(&cal["gyro_matrix"]),
            gyro_bias: vector(&cal["gyro_bias_dps"]),
            true_matrix: matrix(&truth["matrix"]),
            true_offset: vector(&truth["offset"]),
            true_gyro_matrix: matrix(&truth["gyro"]["matrix"]),
            true_gyro_bias: vector(&truth["gyro"]["bias_dps"]),
        }
    })
}

pub fn vector(v: &serde_json::Value) -> [f64; 3] {
    [0, 1, 2].map(|i| v[i].as_f64().unwrap())
}

pub fn matrix(v: &serde_json::Value) -> Mat {
    [0, 1, 2].map(|i| vector(&v[i]))
}

/// Runs accelcal.
pub fn accelcal(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_accelcal")).args(args).output().expect("accelcal runs")
}

/// Exports the simulated calibration to `target`, into a file named `name` beside it; its path.
pub fn export(target: &str, name: &str, extra: &[&str]) -> PathBuf {
    let sim = simulated();
    let path = sim.dir.join(name);
    let mut args = vec!["export", sim.json.to_str().unwrap(), "--to", target, "-o", path.to_str().unwrap()];
    args.extend(extra);
    let output = accelcal(&args);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    path
}

/// M (m - o), accelcal's convention, written out here.
pub fn correct(matrix: &Mat, offset: &[f64; 3], m: [f64; 3]) -> [f64; 3] {
    let d = [m[0] - offset[0], m[1] - offset[1], m[2] - offset[2]];
    [0, 1, 2].map(|i| matrix[i][0] * d[0] + matrix[i][1] * d[1] + matrix[i][2] * d[2])
}

/// `n` random raw readings over the whole int16 range (xorshift64*, fixed seed).
pub fn raw_readings(n: usize) -> Vec<[i16; 3]> {
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut next = move || {
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        (state.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 48) as u16 as i16
    };
    (0..n).map(|_| [next(), next(), next()]).collect()
}

/// Random unit vectors (xorshift64*, Box-Muller normals, normalised), a seed other than the exporter's lattice.
pub fn directions(n: usize) -> Vec<[f64; 3]> {
    let mut state: u64 = 0x1234_5678_9ABC_DEF1;
    let mut uniform = move || {
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        ((state.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    };
    let mut normal = move || (-2.0 * uniform().ln()).sqrt() * (std::f64::consts::TAU * uniform()).cos();
    (0..n)
        .map(|_| {
            let v = [normal(), normal(), normal()];
            let norm = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            v.map(|x| x / norm)
        })
        .collect()
}

/// The inverse of a 3x3 matrix (cofactors).
pub fn inverse(m: &Mat) -> Mat {
    let c = |i: usize, j: usize| {
        let (r0, r1, c0, c1) = ((i + 1) % 3, (i + 2) % 3, (j + 1) % 3, (j + 2) % 3);
        m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0]
    };
    let det = m[0][0] * c(0, 0) + m[0][1] * c(0, 1) + m[0][2] * c(0, 2);
    [0, 1, 2].map(|i| [0, 1, 2].map(|j| c(j, i) / det))
}

/// Whether `program` runs (`program --version`); if not, a failure under CI=true, else a skip said on stderr.
pub fn tool(program: &str, install: &str) -> bool {
    let found = Command::new(program).arg("--version").output().is_ok_and(|o| o.status.success());
    if !found {
        assert!(std::env::var("CI").as_deref() != Ok("true"), "CI=true but {program} is missing ({install})");
        eprintln!("SKIPPED: {program} is not installed ({install}); CI=true makes this a failure");
    }
    found
}

/// Runs a command to success; its stdout.
pub fn run(command: &mut Command) -> String {
    let output = command.output().expect("the tool runs");
    assert!(output.status.success(), "{command:?} failed: {}", String::from_utf8_lossy(&output.stderr));
    String::from_utf8(output.stdout).unwrap()
}

/// Rows of whitespace-separated numbers.
pub fn numbers(text: &str) -> Vec<Vec<f64>> {
    text.lines().map(|l| l.split_whitespace().map(|v| v.parse().unwrap()).collect()).collect()
}

/// The readings as lines of three integers (what the compiled programs read).
pub fn readings_text(readings: &[[i16; 3]]) -> String {
    readings.iter().map(|r| format!("{} {} {}\n", r[0], r[1], r[2])).collect()
}

/// Runs `command` with `input` on stdin; its stdout.
pub fn run_with_input(command: &mut Command, input: &str) -> String {
    use std::io::Write;
    let mut child = command
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("the program runs");
    // NOTE: written from a thread, so that a program whose output fills the pipe before it has read all
    // of its input does not wait on us while we wait on it.
    let (mut stdin, input) = (child.stdin.take().unwrap(), input.to_owned());
    let writer = std::thread::spawn(move || stdin.write_all(input.as_bytes()));
    let output = child.wait_with_output().unwrap();
    let written = writer.join().unwrap();
    assert!(output.status.success(), "{command:?} failed: {}", String::from_utf8_lossy(&output.stderr));
    written.unwrap();
    String::from_utf8(output.stdout).unwrap()
}

/// The stated loss of an export: (rms mg, worst mg, gyro rms %, gyro worst %).
pub fn stated_loss(text: &str) -> (f64, f64, f64, f64) {
    let after = |key: &str| -> Vec<f64> {
        let line = text.lines().find(|l| l.contains(key)).unwrap_or_else(|| panic!("no {key:?} line"));
        let tail = &line[line.find(key).unwrap() + key.len()..];
        tail.split(|c: char| !(c.is_ascii_digit() || c == '.'))
            .filter(|s| !s.is_empty())
            .filter_map(|s| s.parse().ok())
            .collect()
    };
    let accel = after("orientations at 1 g:");
    let gyro = after("of the rate:");
    (accel[0], accel[1], gyro[0], gyro[1])
}

/// Reads a file as text.
pub fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap()
}
