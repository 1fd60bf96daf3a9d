//! The core compiled to WebAssembly and run under node computes, bit for bit, what it computes
//! natively: `simulated_session_json`'s text from the .wasm equals the one from this test's own build.

use std::path::{Path, PathBuf};
use std::process::Command;

use accelcal_web::simulated_session_json;

/// The seeds compared: two, so that one session that happens to agree cannot pass alone.
const SEEDS: [u64; 2] = [1, 7];

/// The workspace's root: the directory above this crate.
fn workspace() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("web/ sits in the workspace")
}

/// Builds the crate for wasm32-unknown-unknown and returns the .wasm's path.
// NOTE: the dev profile, which `.ci/run`'s own wasm32 build has just built: the release profile's fat
// LTO would compile the core once more for a run that takes seconds either way.
fn build_wasm() -> PathBuf {
    // NOTE: cargo runs in the workspace, so a relative CARGO_TARGET_DIR means the same directory to it
    // as to the join below; without one, the workspace's own target directory.
    let status = Command::new(env!("CARGO"))
        .current_dir(workspace())
        .args(["build", "-p", "accelcal-web", "--target", "wasm32-unknown-unknown"])
        .status()
        .expect("cargo runs");
    assert!(status.success(), "building the wasm failed ({status}); its errors are above");
    let target = std::env::var_os("CARGO_TARGET_DIR").map_or_else(|| workspace().join("target"), PathBuf::from);
    workspace().join(target).join("wasm32-unknown-unknown/debug/accelcal_web.wasm")
}

/// What `web/tests/run.mjs` prints for `seed`: the JSON the .wasm computed under node.
fn run_under_node(wasm: &Path, seed: u64) -> String {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/run.mjs");
    let output = match Command::new("node").arg(script).arg(wasm).arg(seed.to_string()).output() {
        Ok(output) => output,
        Err(e) => panic!("node did not start ({e}); this test needs node 18 or newer: apt-get install nodejs"),
    };
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "run.mjs failed for seed {seed} ({}):\n{stderr}", output.status);
    String::from_utf8(output.stdout).expect("run.mjs prints UTF-8")
}

/// Where two texts first differ, in bytes from the start.
fn first_difference(a: &str, b: &str) -> usize {
    a.bytes().zip(b.bytes()).take_while(|(x, y)| x == y).count()
}

#[test]
#[cfg_attr(
    not(has_wasm_node),
    ignore = "needs node (apt-get install nodejs) and the wasm32 target (rustup target add wasm32-unknown-unknown); CI=true runs it"
)]
fn wasm_under_node_prints_the_native_calibration_bit_for_bit() {
    let wasm = build_wasm();
    for seed in SEEDS {
        let (wasm_text, native_text) = (run_under_node(&wasm, seed), simulated_session_json(seed));
        assert!(
            wasm_text == native_text,
            "seed {seed}: wasm and native differ from byte {}\n wasm:   {wasm_text}\n native: {native_text}",
            first_difference(&wasm_text, &native_text)
        );
    }
}

#[test]
fn different_seeds_give_different_calibrations() {
    // NOTE: otherwise the comparison above could pass on a text that holds no computed number.
    let [first, second] = SEEDS.map(simulated_session_json);
    assert_ne!(first, second);
    assert!(first.contains("\"calibration\""), "seed {}: no calibration: {first}", SEEDS[0]);
}
