//! Finds what the web tests need (see host/optional_tools.rs): node and the wasm32 target for the
//! wasm under node; with them Debian's chromium and the page's test packages (npm ci in
//! web/tests/browser) for the page in headless Chromium.

include!("../host/optional_tools.rs");

fn main() {
    // NOTE: the cfgs are for the tests, which build for the host. A wasm32 build (`cargo xtask web`,
    // run by the page tests themselves) must not depend on PATH, which differs under `cargo test`:
    // every page test would otherwise build and link the page's wasm again.
    if std::env::var("TARGET").is_ok_and(|target| target.starts_with("wasm32")) {
        println!("cargo::rerun-if-changed=build.rs");
        return;
    }
    let both = "node --version && rustup target list --installed | grep -qx wasm32-unknown-unknown";
    tool_cfg("has_wasm_node", "sh", &["-c", both]);
    let page = "node --version && rustup target list --installed | grep -qx wasm32-unknown-unknown \
                && wasm-bindgen --version && chromium --version && test -d tests/browser/node_modules/puppeteer-core";
    tool_cfg("has_page_tools", "sh", &["-c", page]);
    // NOTE: npm writes this file on every install: the cfg is found again after `npm ci`.
    println!("cargo::rerun-if-changed=tests/browser/node_modules/.package-lock.json");
}
