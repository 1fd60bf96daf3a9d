//! Long work shows that it is working, with the time so far, on the person's terminal: `fit` on many
//! rows, `noise` on a long recording (the tests give them one with `script`, util-linux's, as the
//! spinner draws only on a terminal).

use std::fmt::Write as _;
use std::process::Command;

/// 10 000 readings of a board with a 1 % scale error and offsets of tens of mg, at orientations
/// spread over the sphere (a Fibonacci lattice), each with a few tenths of a mg of scatter.
fn many_rows() -> String {
    let rows = 10_000;
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    let mut text = String::from("x,y,z\n");
    for i in 0..rows {
        let z = 1.0 - 2.0 * (f64::from(i) + 0.5) / f64::from(rows);
        let (r, angle) = ((1.0 - z * z).sqrt(), golden * f64::from(i));
        let scatter = 3e-4 * (f64::from(i) * 12.9898).sin();
        let reading = [1.01 * r * angle.cos() + 0.02, 0.99 * r * angle.sin() - 0.01, z + 0.03 + scatter];
        let _ = writeln!(text, "{:.6},{:.6},{:.6}", reading[0], reading[1], reading[2]);
    }
    text
}

/// What `command` shows on a terminal of its own, and whether it succeeded.
fn on_a_terminal(command: &str) -> (bool, String) {
    let output =
        Command::new("script").args(["-qfec", command, "/dev/null"]).output().expect("script (util-linux) runs");
    (output.status.success(), String::from_utf8_lossy(&output.stdout).into_owned())
}

#[test]
fn fit_on_ten_thousand_rows_shows_on_the_terminal_that_it_is_working() {
    let file = std::env::temp_dir().join(format!("accelcal-fit-progress-{}.csv", std::process::id()));
    std::fs::write(&file, many_rows()).unwrap();
    let command = format!("{} fit {} --model auto", env!("CARGO_BIN_EXE_accelcal"), file.display());
    let (succeeded, shown) = on_a_terminal(&command);
    assert!(succeeded, "{shown}");
    assert!(shown.contains("fitting 10000 rows (--model auto) ("), "no progress on the terminal: {shown}");
    std::fs::remove_file(file).unwrap();
}

#[test]
fn noise_on_a_recording_shows_on_the_terminal_that_it_is_reading_and_analysing() {
    let file = std::env::temp_dir().join(format!("accelcal-noise-progress-{}.npy", std::process::id()));
    let record = Command::new(env!("CARGO_BIN_EXE_accelcal"))
        .args(["record", "--sim", "--seconds", "20", "--output"])
        .arg(&file)
        .output()
        .unwrap();
    assert!(record.status.success(), "{}", String::from_utf8_lossy(&record.stderr));
    let (succeeded, shown) = on_a_terminal(&format!("{} noise {}", env!("CARGO_BIN_EXE_accelcal"), file.display()));
    assert!(succeeded, "{shown}");
    assert!(shown.contains(&format!("reading {} (", file.display())), "no progress while reading: {shown}");
    assert!(shown.contains("Allan deviation of 20000 samples per axis ("), "no progress while analysing: {shown}");
    assert!(shown.contains("white noise"), "the result follows: {shown}");
    std::fs::remove_file(file).unwrap();
}
