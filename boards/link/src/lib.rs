//! The one build script of every board crate (and of tests/qemu's emulated board): each calls
//! [`link`] with its linker arguments.
//!
//! Those crates are leaves (nothing depends on them), so their link search path reaches only their
//! own binary. Host builds need nothing: there the board binary is empty.

use std::{env, fs, path::PathBuf};

/// Copies the package's `memory.x` (when it has one) where the linker finds it, and passes
/// `arguments` (such as `-Tlink.x`) to the linker, for board builds only.
pub fn link(arguments: &[&str]) {
    link_memory("memory.x", arguments);
}

/// As [`link`], with the memory map from `memory` (a crate of several chips keeps one per chip).
pub fn link_memory(memory: &str, arguments: &[&str]) {
    println!("cargo:rerun-if-changed={memory}");
    println!("cargo:rerun-if-changed=build.rs");
    if env::var("CARGO_CFG_TARGET_OS").as_deref() != Ok("none") {
        return;
    }
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    if fs::exists(memory).unwrap_or(false) {
        fs::copy(memory, out.join("memory.x")).expect("the memory map is readable");
    }
    // NOTE: a search path of its own, not a `-L` link argument: flip-link finds memory.x only there.
    println!("cargo:rustc-link-search={}", out.display());
    for argument in arguments {
        println!("cargo:rustc-link-arg-bins={argument}");
    }
}
