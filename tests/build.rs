//! Finds the optional tools of the workspace tests (see host/optional_tools.rs).

include!("../host/optional_tools.rs");

fn main() {
    tool_cfg("has_allantools", "python3", &["-c", "import numpy, allantools"]);
}
