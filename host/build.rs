//! Finds the optional tools of the host's tests (see optional_tools.rs).

include!("optional_tools.rs");

fn main() {
    tool_cfg("has_chromium", "chromium", &["--version"]);
    tool_cfg("has_numpy", "python3", &["-c", "import numpy"]);
    tool_cfg("has_gcc", "gcc", &["--version"]);
    tool_cfg("has_gxx", "g++", &["--version"]);
    tool_cfg("has_octave", "octave", &["--version"]);
    tool_cfg("has_imufusion", "python3", &["-c", "import imufusion, numpy"]);
    tool_cfg("has_pyyaml", "python3", &["-c", "import yaml"]);
    tool_cfg("has_esphome", "python3", &["-m", "esphome", "version"]);
    tool_cfg("has_openhtf", "python3", &["-c", "import openhtf"]);
    tool_cfg("has_ocptv", "python3", &["-c", "import ocptv"]);
    // NOTE: Debian keeps the server's programs off the PATH, in /usr/lib/postgresql/VERSION/bin.
    tool_cfg("has_postgres", "sh", &["-c", "ls /usr/lib/postgresql/*/bin/initdb || command -v initdb"]);
    // NOTE: the emulated Pico's tests also need dist/accelcal-pico.uf2, which they ask for by name.
    let emulator = "require.resolve('rp2040js', { paths: ['../boards/pico/emulator'] })";
    tool_cfg("has_pico_emulator", "node", &["-e", emulator]);
}
