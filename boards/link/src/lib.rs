//! The one build script of every board crate (and of tests/qemu's emulated board): each calls
//! [`link`] with its linker scripts.
//!
//! Those crates are leaves (nothing depends on them), so their link search path reaches only their
//! own binary. Host builds need nothing: there the board binary is empty.

use std::{env, fs, path::PathBuf};

/// Copies the package's `memory.x` (when it has one) where the linker finds it, and passes
/// `scripts` (such as `link.x`) to the linker, for board builds only.
pub fn link(scripts: &[&str]) {
    println!("cargo:rerun-if-changed=memory.x");
    println!("cargo:rerun-if-changed=build.rs");
    if env::var("CARGO_CFG_TARGET_OS").as_deref() != Ok("none") {
        return;
    }
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    if fs::exists("memory.x").unwrap_or(false) {
        fs::copy("memory.x", out.join("memory.x")).expect("memory.x is readable");
    }
    // NOTE: a search path of its own, not a `-L` link argument: flip-link finds memory.x only there.
    println!("cargo:rustc-link-search={}", out.display());
    for script in scripts {
        println!("cargo:rustc-link-arg-bins=-T{script}");
    }
}
