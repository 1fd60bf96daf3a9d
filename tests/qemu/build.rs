//! Links the on-target binaries; for the host's tests, finds whether they can run here.

use std::path::{Path, PathBuf};

fn main() {
    let rust_target = std::env::var("TARGET").unwrap_or_default();
    if std::env::var("CARGO_CFG_TARGET_ARCH").as_deref() == Ok("riscv32") {
        // NOTE: riscv-rt's link.x, on the virt machine's memory map (only `fit-count` is built for it).
        board_link::link_memory("memory-riscv32.x", &["-Tlink.x"]);
    } else if rust_target.starts_with("thumbv6m") {
        // NOTE: cortex-m-rt's link.x on the micro:bit's memory map (only `fit-count` is built for it);
        // .cargo/config.toml adds link.x for thumbv7em alone.
        board_link::link_memory("memory-cortex-m0.x", &["--nmagic", "-Tlink.x"]);
    } else {
        // NOTE: link.x comes from .cargo/config.toml for every thumbv7em build.
        board_link::link(&[]);
    }
    println!("cargo::rerun-if-env-changed=CI");
    println!("cargo::rerun-if-env-changed=PATH");
    println!("cargo::rerun-if-env-changed=CARGO_TARGET_DIR");
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../target"));
    runnable_cfg("on_target_runnable", "qemu-system-arm", &target.join("thumbv7em-none-eabihf/release"), &ELFS);
    runnable_cfg("m0_runnable", "qemu-system-arm", &target.join("thumbv6m-none-eabi/release"), &FIT_COUNT);
    runnable_cfg(
        "rv32_runnable",
        "qemu-system-riscv32",
        &target.join("riscv32imc-unknown-none-elf/release"),
        &FIT_COUNT,
    );
}

/// The on-target binaries the tests run under QEMU (tests/common/mod.rs names the same).
const ELFS: [&str; 2] = ["qemu-tests", "fit-count"];
/// The one built for the Cortex-M0 and the generic RV32IMC.
const FIT_COUNT: [&str; 1] = ["fit-count"];

/// Sets `cfg` when `qemu` runs and the binaries `elfs` are built in `release`, or when CI=true
/// (where a missing one must fail): the tests read it in `#[cfg_attr(not(..), ignore)]`, so a test
/// that cannot run here is reported as ignored with its reason, never "ok".
fn runnable_cfg(cfg: &str, qemu: &str, release: &Path, elfs: &[&str]) {
    println!("cargo::rustc-check-cfg=cfg({cfg})");
    // NOTE: a binary built later changes its file, which runs this script again.
    elfs.iter().for_each(|elf| println!("cargo::rerun-if-changed={}", release.join(elf).display()));
    let built = elfs.iter().all(|elf| release.join(elf).exists());
    let runs = std::process::Command::new(qemu).arg("--version").output().is_ok_and(|o| o.status.success());
    if (built && runs) || std::env::var("CI").as_deref() == Ok("true") {
        println!("cargo::rustc-cfg={cfg}");
    }
}
