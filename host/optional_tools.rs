// The optional tools some tests compare against, found when the crate is built: each found tool
// (or CI=true, where a missing one must fail) sets a cfg that the test's `#[cfg_attr(not(..), ignore)]`
// reads, so a test that cannot run where it is run is reported as ignored with its reason, never "ok".
// Included by host/build.rs and tests/build.rs.

/// Sets `cfg` when `program args` runs and succeeds, or when CI=true.
fn tool_cfg(cfg: &str, program: &str, args: &[&str]) {
    println!("cargo::rustc-check-cfg=cfg({cfg})");
    println!("cargo::rerun-if-env-changed=CI");
    println!("cargo::rerun-if-env-changed=PATH");
    let ci = std::env::var("CI").as_deref() == Ok("true");
    let found = std::process::Command::new(program).args(args).output().is_ok_and(|o| o.status.success());
    if found || ci {
        println!("cargo::rustc-cfg={cfg}");
    }
}
