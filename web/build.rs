//! Finds what the wasm test needs (see host/optional_tools.rs): node, and the wasm32 target to build for.

include!("../host/optional_tools.rs");

fn main() {
    let both = "node --version && rustup target list --installed | grep -qx wasm32-unknown-unknown";
    tool_cfg("has_wasm_node", "sh", &["-c", both]);
}
