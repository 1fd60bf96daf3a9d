//! Nothing is overwritten or dropped without asking: sessions are refused rather than replaced,
//! their names keep their dots, a folder gets a session inside it, and a capture stores what it
//! was asked for; and what the parser accepts can succeed.

mod common;

use std::path::{Path, PathBuf};
use std::process::Output;
use std::time::Duration;

fn accelcal(args: &[&str]) -> Output {
    common::accelcal_within(args, Duration::from_secs(120)).0
}

/// A fresh folder of its own for one test.
fn folder(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("accelcal-lost-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn quick_session(session: &Path) -> Output {
    accelcal(&["calibrate", "--sim", "--chip-fit", "--yes", "--session", session.to_str().unwrap()])
}

#[test]
fn a_second_calibration_into_a_kept_session_is_refused_pointing_to_resume_and_the_session_is_untouched() {
    let dir = folder("again");
    let stem = dir.join("board");
    assert!(quick_session(&stem).status.success());
    let before = std::fs::read(dir.join("board.json")).unwrap();
    let again = quick_session(&stem);
    let stderr = String::from_utf8_lossy(&again.stderr);
    assert!(!again.status.success(), "{stderr}");
    assert!(stderr.contains("already holds a session") && stderr.contains("--resume"), "{stderr}");
    assert_eq!(std::fs::read(dir.join("board.json")).unwrap(), before, "the kept session was rewritten");
}

#[test]
fn session_names_keep_their_dots() {
    let dir = folder("dots");
    assert!(quick_session(&dir.join("board.1")).status.success());
    assert!(quick_session(&dir.join("board.2")).status.success());
    for name in ["board.1.json", "board.1.csv", "board.2.json", "board.2.csv"] {
        assert!(dir.join(name).exists(), "{name} missing");
    }
    assert!(!dir.join("board.json").exists());
}

#[test]
fn a_session_given_as_a_folder_is_kept_inside_it() {
    let dir = folder("dir");
    let given = format!("{}/sessions/", dir.display());
    let output = quick_session(Path::new(&given));
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let inside: Vec<_> = std::fs::read_dir(dir.join("sessions")).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert!(inside.iter().any(|n| n.to_string_lossy().ends_with(".json")), "{inside:?}");
    assert!(!dir.join("sessions.json").exists());
}

#[test]
fn a_simulated_capture_named_as_a_face_stores_that_face() {
    let dir = folder("capture");
    let stem = dir.join("named.1");
    for name in ["+X", "-Y"] {
        let name = format!("--name={name}");
        let output = accelcal(&["capture", "--sim", &name, "--seconds", "5", "--session", stem.to_str().unwrap()]);
        assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    }
    let json: serde_json::Value = serde_json::from_slice(&std::fs::read(dir.join("named.1.json")).unwrap()).unwrap();
    let mean = |i: usize, k: usize| json["captures"][i]["stats"]["mean_g"][k].as_f64().unwrap();
    // NOTE: the simulated sensor's offsets and scale errors are within 0.1 g.
    assert!((mean(0, 0) - 1.0).abs() < 0.1, "+X reads {}", mean(0, 0));
    assert!((mean(1, 1) + 1.0).abs() < 0.1, "-Y reads {}", mean(1, 1));
}

#[test]
fn the_largest_values_the_parser_accepts_succeed_with_the_simulated_hand() {
    for extra in [&["--chip-fit", "--verify", "16"][..], &["--sim-placement-deg", "8"][..]] {
        let args = [&["calibrate", "--sim", "--yes", "--seed", "3"][..], extra].concat();
        // NOTE: --verify 20 and --sim-placement-deg 10 waited 60 s and failed: the parser refuses them now.
        let output = accelcal(&args);
        assert!(output.status.success(), "{extra:?}: {}", String::from_utf8_lossy(&output.stderr));
    }
}

#[test]
fn a_second_run_into_a_session_another_run_is_writing_is_refused_naming_that_run_and_the_first_keeps_it() {
    use common::person::{Moves, Run};
    let dir = folder("held");
    let stem = dir.join("z");
    let mut board = common::SimPty::start(&[]);
    let mut first =
        Run::start(&board.path, &["--chip-fit", "--yes", "--session", stem.to_str().unwrap()], Moves::Place);
    // NOTE: the person has not moved the board yet: the first run waits at its first position.
    assert!(first.follow(&mut board, "the captures are kept in").is_some(), "{}", first.seen.join("\n"));
    let serial = serde_json::from_slice::<serde_json::Value>(&std::fs::read(dir.join("z.json")).unwrap()).unwrap()
        ["board"]["serial"]
        .as_str()
        .unwrap()
        .to_owned();
    let second = quick_session(&stem);
    let stderr = String::from_utf8_lossy(&second.stderr);
    assert!(!second.status.success(), "{stderr}");
    let holder =
        format!("z.json is being written by another run of accelcal (pid {}, board {serial})", first.child.id());
    assert!(stderr.contains(&holder) && stderr.contains("or give another --session name"), "{stderr}");
    // Ctrl-C ends the first run with its session kept, and its lock gone with it.
    first.interrupt();
    let (status, _, seen) = first.finish(&mut board);
    assert!(!status.success(), "{seen}");
    let kept: serde_json::Value = serde_json::from_slice(&std::fs::read(dir.join("z.json")).unwrap()).unwrap();
    assert_eq!(kept["board"]["serial"], serial.as_str());
    assert!(!dir.join("z.json.lock").exists(), "the lock file is left after Ctrl-C");
}

/// `accelcal ARGS` run in `dir` with every file it writes limited to `blocks` of 512 bytes
/// (RLIMIT_FSIZE, SIGXFSZ ignored): a write past the limit is cut short and fails with EFBIG, as
/// on a full disk.
fn with_file_limit(dir: &Path, blocks: u64, args: &[&str]) -> (std::process::ExitStatus, String) {
    let mut child = std::process::Command::new("sh")
        .args(["-c", "ulimit -f \"$0\" && trap '' XFSZ && exec \"$@\"", &blocks.to_string()])
        .arg(env!("CARGO_BIN_EXE_accelcal"))
        .args(args)
        .current_dir(dir)
        .stdout(std::process::Stdio::null())
        .stderr(std::fs::File::create(dir.join("stderr.txt")).unwrap())
        .spawn()
        .unwrap();
    let status = common::wait_or_kill(&mut child, Duration::from_secs(120));
    (status, std::fs::read_to_string(dir.join("stderr.txt")).unwrap())
}

/// The session file's JSON, and no temporary file left beside it.
fn kept_whole(dir: &Path) -> serde_json::Value {
    let names: Vec<String> =
        std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    assert!(!names.iter().any(|n| n.contains(".tmp")), "a failed write left its temporary: {names:?}");
    serde_json::from_slice(&std::fs::read(dir.join("z.json")).unwrap()).unwrap()
}

const QUICK: [&str; 6] = ["calibrate", "--sim", "--chip-fit", "--yes", "--session", "z"];

#[test]
fn on_a_full_disk_the_captures_said_to_be_kept_are_those_the_session_file_holds() {
    let dir = folder("full-captures");
    // NOTE: 4 KiB holds the empty session and a few captures, not all ten.
    let (status, stderr) = with_file_limit(&dir, 8, &QUICK);
    assert!(!status.success(), "{stderr}");
    let kept = kept_whole(&dir)["captures"].as_array().unwrap().len();
    assert!(kept > 0 && kept < 10, "{kept} captures: {stderr}");
    assert!(stderr.contains("File too large"), "{stderr}");
    let said = format!(
        "{kept} captures so far are kept in z.json: continue with `accelcal calibrate --sim --seed 1 --resume z.json`"
    );
    assert!(stderr.contains(&said), "the file holds {kept}: {stderr}");
}

#[test]
fn on_a_full_disk_a_verification_that_cannot_be_kept_says_so_with_the_resume_line() {
    let whole = folder("full-whole");
    let (status, stderr) = with_file_limit(&whole, 1 << 20, &QUICK);
    assert!(status.success(), "{stderr}");
    let mut session = kept_whole(&whole);
    let verified_bytes = serde_json::to_string_pretty(&session).unwrap().len() as u64;
    session.as_object_mut().unwrap().remove("verification");
    let uploaded_bytes = serde_json::to_string_pretty(&session).unwrap().len() as u64;
    // NOTE: room for the session as uploaded, not for it with its verification.
    let blocks = (uploaded_bytes + verified_bytes) / 2 / 512;
    assert!(
        blocks * 512 > uploaded_bytes + 64 && blocks * 512 + 64 < verified_bytes,
        "{uploaded_bytes} {verified_bytes}"
    );
    let dir = folder("full-verification");
    let (status, stderr) = with_file_limit(&dir, blocks, &QUICK);
    assert!(!status.success(), "{stderr}");
    assert!(stderr.contains("the verification is not kept"), "{stderr}");
    assert!(stderr.contains("check it again with `accelcal calibrate --sim --seed 1 --resume z.json`"), "{stderr}");
    let kept = kept_whole(&dir);
    assert!(kept.get("uploaded").is_some() && kept.get("verification").is_none(), "{kept}");
    assert_eq!(kept["captures"].as_array().unwrap().len(), 10);
}

/// Runs `accelcal ARGS`, which must succeed.
fn succeeds(args: &[&str]) {
    let output = accelcal(args);
    assert!(output.status.success(), "{args:?}: {}", String::from_utf8_lossy(&output.stderr));
}

/// Runs `accelcal ARGS`, which must refuse to replace `path`, leaving it as it was, and name it
/// with the flag that replaces it; then with that flag, which must replace it.
fn kept_unless_overwrite(args: &[&str], path: &Path) {
    let before = std::fs::read(path).unwrap();
    let refused = accelcal(args);
    let stderr = String::from_utf8_lossy(&refused.stderr);
    assert!(!refused.status.success(), "{args:?}: {stderr}");
    let said = format!("{} already exists: ", path.display());
    assert!(stderr.contains(&said) && stderr.contains("or add --overwrite to replace it"), "{args:?}: {stderr}");
    assert_eq!(std::fs::read(path).unwrap(), before, "{args:?} changed {}", path.display());
    succeeds(&[args, &["--overwrite"]].concat());
    assert_ne!(std::fs::read(path).unwrap(), before, "{args:?} --overwrite left {}", path.display());
}

#[test]
fn a_recording_a_certificate_or_an_export_already_there_is_kept_unless_overwrite_is_given() {
    let dir = folder("overwrite");
    let recording = dir.join("long.npy");
    let record = |seconds: &'static str| ["record", "--sim", "--rate", "100", "--seconds", seconds, "-o"];
    succeeds(&[&record("3")[..], &[recording.to_str().unwrap()]].concat());
    kept_unless_overwrite(&[&record("1")[..], &[recording.to_str().unwrap()]].concat(), &recording);
    // `calibrate` issued the session's certificate: issuing it again would replace it.
    assert!(quick_session(&dir.join("z")).status.success());
    let (session, certificate) = (dir.join("z.json"), dir.join("z.certificate.json"));
    // NOTE: issued again within the minute, the certificate is the same bytes: a mark tells them apart.
    std::fs::write(&certificate, [std::fs::read(&certificate).unwrap(), b"\n".to_vec()].concat()).unwrap();
    kept_unless_overwrite(&["certificate", "issue", session.to_str().unwrap()], &certificate);
    let header = dir.join("cal.h");
    std::fs::write(&header, "// a person's own file\n").unwrap();
    kept_unless_overwrite(&["export", session.to_str().unwrap(), "--to", "c", "-o", header.to_str().unwrap()], &header);
}

#[test]
fn ctrl_c_at_the_upload_question_ends_the_run_at_once_with_the_resume_line() {
    use std::io::Read;
    use std::os::fd::FromRawFd;
    let dir = folder("question");
    let stem = dir.join("z");
    // NOTE: the question is asked only of a terminal: stdin is a pseudo-terminal, its master held open.
    let terminal = nix::pty::openpty(None, None).unwrap();
    let (_master, stdin) =
        unsafe { (std::fs::File::from_raw_fd(terminal.master), std::fs::File::from_raw_fd(terminal.slave)) };
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_accelcal"))
        .args(["calibrate", "--sim", "--chip-fit", "--session", stem.to_str().unwrap()])
        .stdin(stdin)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let said = std::sync::Arc::new(std::sync::Mutex::new(String::new()));
    let mut stderr = child.stderr.take().unwrap();
    let heard = said.clone();
    std::thread::spawn(move || {
        let mut buffer = [0u8; 1024];
        while let Ok(n @ 1..) = stderr.read(&mut buffer) {
            heard.lock().unwrap().push_str(&String::from_utf8_lossy(&buffer[..n]));
        }
    });
    let asked = std::time::Instant::now();
    while !said.lock().unwrap().contains("[y/N]") {
        assert!(asked.elapsed() < Duration::from_secs(60), "never asked: {}", said.lock().unwrap());
        std::thread::sleep(Duration::from_millis(50));
    }
    std::process::Command::new("kill").args(["-INT", &child.id().to_string()]).status().unwrap();
    // NOTE: before, the run waited for Enter: killed after 5 s, the helper fails the test as a hang.
    let status = common::wait_or_kill(&mut child, Duration::from_secs(5));
    std::thread::sleep(Duration::from_millis(100));
    let said = said.lock().unwrap().clone();
    assert!(!status.success(), "{said}");
    let resume = format!(
        "10 captures so far are kept in {}: continue with `accelcal calibrate --sim --seed 1 --resume",
        stem.with_extension("json").display()
    );
    assert!(said.contains(&resume), "{said}");
    assert!(!said.contains("not uploaded"), "{said}");
}
