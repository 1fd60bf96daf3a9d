//! Finding the on-target binaries and QEMU, for the tests that run them. Each such test is
//! `#[cfg_attr(not(on_target_runnable), ignore = ...)]` (or `m0_runnable`, `rv32_runnable`): where tests/qemu/build.rs
//! found QEMU or the binaries missing (and CI is not true) it is reported as ignored with its reason,
//! never "ok".

// NOTE: each test binary uses a part of these helpers.
#![allow(dead_code)]

use std::path::PathBuf;
use std::process::Command;

/// An emulated chip: the target its binaries are built for and the QEMU that runs them.
pub struct Chip {
    /// The Rust target.
    pub target: &'static str,
    /// The QEMU program and the Debian package that has it.
    pub qemu: &'static str,
    pub package: &'static str,
    /// QEMU's arguments for the machine, before `-kernel ELF`.
    pub machine: &'static [&'static str],
}

/// QEMU's netduinoplus2, an STM32F405: a Cortex-M4F with the F411's flash and RAM addresses.
pub const CORTEX_M4F: Chip = Chip {
    target: "thumbv7em-none-eabihf",
    qemu: "qemu-system-arm",
    package: "qemu-system-arm",
    machine: &["-machine", "netduinoplus2"],
};

/// QEMU's micro:bit, an nRF51822: a Cortex-M0, the ARMv6-M instruction set of the Pico's RP2040
/// (a Cortex-M0+), without an FPU.
pub const CORTEX_M0: Chip = Chip {
    target: "thumbv6m-none-eabi",
    qemu: "qemu-system-arm",
    package: "qemu-system-arm",
    machine: &["-machine", "microbit"],
};

/// QEMU's virt machine with a generic RV32IMC, the ESP32-C3's instruction set (no FPU: its F and D
/// extensions are switched off, so an instruction the target lacks would fault rather than run).
pub const RV32IMC: Chip = Chip {
    target: "riscv32imc-unknown-none-elf",
    qemu: "qemu-system-riscv32",
    package: "qemu-system-misc",
    machine: &["-machine", "virt", "-cpu", "rv32,f=false,d=false", "-bios", "none"],
};

impl Chip {
    /// The on-target binary `name`, built by `cargo build -p qemu-tests --release --target TARGET`.
    pub fn elf(&self, name: &str) -> PathBuf {
        let target = std::env::var_os("CARGO_TARGET_DIR")
            .map(PathBuf::from)
            .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../target"));
        target.join(self.target).join("release").join(name)
    }

    /// The binary `name`; under CI=true, where the build could not find it or QEMU, the test fails
    /// naming what is missing.
    pub fn runnable(&self, name: &str) -> PathBuf {
        let elf = self.elf(name);
        let build = format!("cargo build -p qemu-tests --release --target {} --bin {name}", self.target);
        assert!(elf.exists(), "on-target test cannot run: {} is not built ({build})", elf.display());
        let runs = Command::new(self.qemu).arg("--version").output().is_ok_and(|o| o.status.success());
        assert!(runs, "on-target test cannot run: {} does not run (apt-get install {})", self.qemu, self.package);
        elf
    }

    /// QEMU with this chip's machine and semihosting (its output on stdout), to run `-kernel ELF`.
    pub fn qemu(&self) -> Command {
        let mut qemu = Command::new(self.qemu);
        qemu.args(self.machine).args(["-nographic", "-semihosting-config", "enable=on,target=native"]);
        qemu
    }
}
