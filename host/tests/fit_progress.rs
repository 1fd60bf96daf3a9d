//! `fit` on many rows shows that it is working, with the time so far, on the person's terminal
//! (the test gives it one with `script`, util-linux's, as the spinner draws only on a terminal).

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

#[test]
fn fit_on_ten_thousand_rows_shows_on_the_terminal_that_it_is_working() {
    let file = std::env::temp_dir().join(format!("accelcal-fit-progress-{}.csv", std::process::id()));
    std::fs::write(&file, many_rows()).unwrap();
    let command = format!("{} fit {} --model auto", env!("CARGO_BIN_EXE_accelcal"), file.display());
    let output =
        Command::new("script").args(["-qfec", &command, "/dev/null"]).output().expect("script (util-linux) runs");
    let shown = String::from_utf8_lossy(&output.stdout);
    assert!(output.status.success(), "{shown}");
    assert!(shown.contains("fitting 10000 rows (--model auto) ("), "no progress on the terminal: {shown}");
    std::fs::remove_file(file).unwrap();
}
