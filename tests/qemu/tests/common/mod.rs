//! Finding the on-target binaries and QEMU, for the tests that run them. Each such test is
//! `#[cfg_attr(not(on_target_runnable), ignore = ...)]`: where tests/qemu/build.rs found QEMU or the
//! binaries missing (and CI is not true) it is reported as ignored with its reason, never "ok".

use std::path::PathBuf;
use std::process::Command;

/// The on-target binary `name`, built by `cargo build -p qemu-tests --release --target thumbv7em-none-eabihf`.
pub fn elf(name: &str) -> PathBuf {
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../target"));
    target.join("thumbv7em-none-eabihf/release").join(name)
}

/// The binary `name`; under CI=true, where the build could not find it or QEMU, the test fails
/// naming what is missing.
pub fn runnable(name: &str) -> PathBuf {
    let elf = elf(name);
    let build = "cargo build -p qemu-tests --release --target thumbv7em-none-eabihf";
    assert!(elf.exists(), "on-target test cannot run: {} is not built ({build})", elf.display());
    let qemu = Command::new("qemu-system-arm").arg("--version").output();
    let runs = qemu.is_ok_and(|o| o.status.success());
    assert!(runs, "on-target test cannot run: qemu-system-arm does not run (apt-get install qemu-system-arm)");
    elf
}
