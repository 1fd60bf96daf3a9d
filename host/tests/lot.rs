//! The lot database across processes (issue 28): a writer killed inside a board's transaction leaves
//! the lot as it was before that board, and another process reads the lot while a session writes.

mod common;

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::Duration;

use accelcal::lot::Lot;
use common::accelcal_within;

/// The variable that makes each lot write pause inside its transaction (host/src/cli/lot.rs).
const PAUSE_IN_WRITE: &str = "ACCELCAL_TEST_LOT_PAUSE_S";
const LIMIT: Duration = Duration::from_secs(120);

fn fresh_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("accelcal-lot-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn text(path: &Path) -> &str {
    path.to_str().unwrap()
}

/// A quick simulated calibration of board `seed`, kept in `dir`; its certificate file.
fn certificate(dir: &Path, seed: u64) -> PathBuf {
    let session = dir.join(format!("board{seed}"));
    let seed = seed.to_string();
    let args = ["calibrate", "--sim", "--chip-fit", "--yes", "--seed", &seed, "--session", text(&session)];
    let (output, _) = accelcal_within(&args, LIMIT);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    session.with_extension("certificate.json")
}

/// `accelcal ARGS` with every lot write pausing inside its transaction, returned once it is there.
fn writer_inside_its_transaction(args: &[&str]) -> Child {
    let mut child = Command::new(env!("CARGO_BIN_EXE_accelcal"))
        .args(args)
        .env(PAUSE_IN_WRITE, "60")
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let lines = BufReader::new(child.stderr.take().unwrap()).lines();
    let inside = lines.map_while(Result::ok).any(|line| line.contains("inside the transaction of board"));
    assert!(inside, "the writer ended without reaching its transaction");
    child
}

/// Boards in the lot as `lot show --json` (another process) reads them.
fn boards_read_by_another_process(lot: &Path) -> u64 {
    let (output, _) = accelcal_within(&["lot", "show", text(lot), "--json"], LIMIT);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let summary: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    summary["boards"].as_u64().unwrap()
}

#[test]
fn a_writer_killed_inside_a_board_s_transaction_leaves_the_lot_as_it_was_before_that_board() {
    let dir = fresh_dir("killed");
    let (first, second, lot) = (certificate(&dir, 1), certificate(&dir, 2), dir.join("lot.sqlite"));
    let (output, _) = accelcal_within(&["lot", "add", text(&lot), text(&first)], LIMIT);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let mut writer = writer_inside_its_transaction(&["lot", "add", text(&lot), text(&second)]);
    writer.kill().unwrap();
    writer.wait().unwrap();
    let consistency = Lot::open_existing(&lot).unwrap().consistency().unwrap();
    // NOTE: a quick session's certificate states ortho9's 9 parameters.
    assert_eq!((consistency.certificates, consistency.parameters, consistency.complete), (1, 9, true));
    assert_eq!(boards_read_by_another_process(&lot), 1);
    let (output, _) = accelcal_within(&["lot", "add", text(&lot), text(&second)], LIMIT);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    assert_eq!(boards_read_by_another_process(&lot), 2);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn another_process_reads_the_lot_while_a_session_writes_to_it() {
    let dir = fresh_dir("concurrent");
    let lot = dir.join("lot.sqlite");
    let (output, _) = accelcal_within(&["lot", "add", text(&lot), text(&certificate(&dir, 1))], LIMIT);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let session = dir.join("board2");
    let args =
        ["calibrate", "--sim", "--chip-fit", "--yes", "--seed", "2", "--session", text(&session), "--lot", text(&lot)];
    let mut writer = writer_inside_its_transaction(&args);
    // The reader sees the lot as it was before the board being written, while the writer still
    // holds its transaction open (it pauses there for 60 s).
    assert_eq!(boards_read_by_another_process(&lot), 1);
    assert!(writer.try_wait().unwrap().is_none(), "the writer ended before the read: nothing was shown");
    writer.kill().unwrap();
    writer.wait().unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
}
