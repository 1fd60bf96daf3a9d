//! Links the on-target binaries; for the host's tests, finds whether they can run here.

fn main() {
    // NOTE: link.x comes from .cargo/config.toml for every thumbv7em build.
    board_link::link(&[]);
    on_target_cfg();
}

/// The on-target binaries the tests run under QEMU (tests/common/mod.rs names the same).
const ELFS: [&str; 2] = ["qemu-tests", "fit-count"];

/// Sets `on_target_runnable` when qemu-system-arm runs and the on-target binaries are built, or when
/// CI=true (where a missing one must fail): the tests read it in `#[cfg_attr(not(..), ignore)]`, so
/// a test that cannot run here is reported as ignored with its reason, never "ok".
fn on_target_cfg() {
    println!("cargo::rustc-check-cfg=cfg(on_target_runnable)");
    println!("cargo::rerun-if-env-changed=CI");
    println!("cargo::rerun-if-env-changed=PATH");
    println!("cargo::rerun-if-env-changed=CARGO_TARGET_DIR");
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(std::path::PathBuf::from)
        .unwrap_or_else(|| std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../target"));
    let release = target.join("thumbv7em-none-eabihf/release");
    // NOTE: a binary built later changes its file, which runs this script again.
    ELFS.iter().for_each(|elf| println!("cargo::rerun-if-changed={}", release.join(elf).display()));
    let built = ELFS.iter().all(|elf| release.join(elf).exists());
    let qemu =
        std::process::Command::new("qemu-system-arm").arg("--version").output().is_ok_and(|o| o.status.success());
    if (built && qemu) || std::env::var("CI").as_deref() == Ok("true") {
        println!("cargo::rustc-cfg=on_target_runnable");
    }
}
