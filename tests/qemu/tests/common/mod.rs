//! Finding the on-target binaries and QEMU, for the tests that run them.

use std::path::PathBuf;
use std::process::Command;

/// The on-target binary `name`, built by `cargo build -p qemu-tests --release --target thumbv7em-none-eabihf`.
pub fn elf(name: &str) -> PathBuf {
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../target"));
    target.join("thumbv7em-none-eabihf/release").join(name)
}

/// The binary `name` when it and QEMU are there; otherwise says on the terminal that the test was
/// skipped and why, and fails under CI (`CI` set), where their absence is a fault.
///
/// NOTE: the test harness captures `println!` and `eprintln!` of passing tests; a write to the
/// stderr handle itself is not captured, so a skip is never silent.
pub fn runnable(name: &str) -> Option<PathBuf> {
    use std::io::Write;
    let elf = elf(name);
    let missing = if !elf.exists() {
        format!("{} is not built", elf.display())
    } else if Command::new("qemu-system-arm").arg("--version").output().is_err() {
        "qemu-system-arm is not installed (apt-get install qemu-system-arm)".to_owned()
    } else {
        return Some(elf);
    };
    assert!(std::env::var_os("CI").is_none(), "on-target test cannot run under CI: {missing}");
    let _ = writeln!(std::io::stderr(), "on-target test SKIPPED: {missing}");
    None
}
