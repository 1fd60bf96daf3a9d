//! Puts the workspace's `memory.x` on the linker path for the board build (cortex-m-rt's link.x
//! includes it). Host builds of the library need nothing.

use std::{env, fs, path::PathBuf};

fn main() {
    println!("cargo:rerun-if-changed=../memory.x");
    println!("cargo:rerun-if-changed=build.rs");
    if env::var("CARGO_CFG_TARGET_OS").as_deref() != Ok("none") {
        return;
    }
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    fs::copy("../memory.x", out.join("memory.x")).expect("memory.x is at the workspace root");
    // NOTE: link arguments for this package's binary only: a plain link-search would also reach every
    // crate that depends on the firmware library (tests/qemu links for another memory map).
    println!("cargo:rustc-link-arg-bins=-L{}", out.display());
    println!("cargo:rustc-link-arg-bins=-Tdefmt.x");
}
