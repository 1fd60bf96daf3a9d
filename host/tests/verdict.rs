//! `calibrate` ends with a verdict against `--target-mg`: reached, or missed with why; a
//! calibration that misses by more than its noise ends the command with status 2 (shown end to end
//! on a simulated board whose surroundings heat up once the calibration is uploaded).

mod common;

use std::time::Duration;

use common::person::{Moves, Run};
use common::SimPty;

fn calibrate(extra: &[&str]) -> (Option<i32>, serde_json::Value, String) {
    let args = [&["calibrate", "--sim", "--yes", "--json"], extra].concat();
    let (output, _) = common::accelcal_within(&args, Duration::from_secs(300));
    let json = serde_json::from_slice(&output.stdout).unwrap_or_default();
    (output.status.code(), json, String::from_utf8_lossy(&output.stderr).into_owned())
}

#[test]
fn a_target_reached_ends_with_status_0_and_says_so() {
    let (code, json, stderr) = calibrate(&["--sim-sensor", "settled", "--target-mg", "2"]);
    assert_eq!(code, Some(0), "{stderr}");
    let target = &json["target"];
    assert_eq!(target["target_mg"], 2.0);
    assert_eq!(target["reached"], true, "{target}");
    assert!(target["line"].as_str().unwrap().ends_with(": reached"), "{target}");
}

#[test]
fn a_fixed_length_calibration_is_judged_trusted_or_not_without_a_target() {
    let (code, json, stderr) = calibrate(&["--chip-fit"]);
    assert_eq!(code, Some(0), "{stderr}");
    let line = json["target"]["line"].as_str().unwrap();
    assert!(json["target"]["target_mg"].is_null() && line.contains("aim at no --target-mg"), "{line}");
}

#[test]
fn a_board_that_warms_between_the_captures_and_the_check_misses_its_target_with_status_2_and_says_why() {
    let mut sim = SimPty::with_seed("23", &["--fast"]);
    let session = std::env::temp_dir().join(format!("accelcal-verdict-{}-warmed", std::process::id()));
    let args = ["--yes", "--target-mg", "0.2", "--session", session.to_str().unwrap()];
    let mut run = Run::start(&sim.path.clone(), &args, Moves::Place);
    assert!(run.follow(&mut sim, "uploaded and saved; now checking").is_some(), "{:?}", run.seen);
    // NOTE: the surroundings jump from 20 to 85 degC while the person waits before the check: the die
    // warms by about 5 degC in 20 s (a four-minute time constant), and the offsets drift about a mg
    // per degC with it.
    sim.tell("ambient 85");
    std::thread::sleep(Duration::from_secs(20));
    let (status, stdout, stderr) = run.finish(&mut sim);
    let said = format!("{stdout}\n{stderr}");
    assert_eq!(status.code(), Some(2), "{said}");
    let verdict = said.lines().find(|line| line.starts_with("target 0.2 mg:")).expect("a verdict line");
    println!("{}\n{verdict}", said.lines().filter(|line| line.starts_with("verifi")).collect::<Vec<_>>().join("\n"));
    assert!(
        verdict.contains("not trusted")
            && verdict.contains("missed; the calibration leaves an error the verification resolves"),
        "{verdict}"
    );
    for kept in ["json", "csv", "html", "certificate.json", "certificate.html"] {
        let _ = std::fs::remove_file(session.with_extension(kept));
    }
}

/// Issue 40: `--quick` took 129-130 s of board time against 56-59 s for the default and was "not
/// trusted" at every seed; it is now the default adaptive session for a looser target, which each
/// capture reaches at its shortest: shorter than the default and its target reached.
#[test]
fn quick_is_shorter_than_the_default_and_reaches_its_target() {
    for seed in ["1", "5"] {
        let (code, quick, stderr) = calibrate(&["--quick", "--seed", seed]);
        assert_eq!(code, Some(0), "seed {seed}: {stderr}");
        let (_, default, _) = calibrate(&["--seed", seed]);
        let seconds = |json: &serde_json::Value| json["board_seconds"].as_f64().expect("board seconds");
        let (short, full) = (seconds(&quick), seconds(&default));
        assert!(short < 0.7 * full, "seed {seed}: --quick took {short} s of board time, the default {full} s");
        let target = &quick["target"];
        assert_eq!(target["target_mg"], 2.0, "seed {seed}: {target}");
        assert!(target["reached"] == true && target["trusted"] == true, "seed {seed}: {target}");
    }
}
