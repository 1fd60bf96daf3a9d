//! Why the emulated Pico could not run: below the bridge, its harness and its port, which all fail with it.

use std::path::PathBuf;

/// Why the emulated Pico could not run.
#[derive(Debug, thiserror::Error)]
pub enum EmulatorError {
    #[error("cannot run the emulator with node ({0}); install Node.js 18 or later")]
    Node(String),
    #[error("the emulator is not installed in {0}; run `npm ci` there")]
    NotInstalled(PathBuf),
    #[error("no firmware at {0}; `cargo xtask dist` writes dist/accelcal-pico.uf2")]
    NoFirmware(PathBuf),
    #[error("the emulator ended ({0}); it says why on stderr")]
    Ended(String),
    #[error("the emulator sent a line the bridge does not know: {0:?}")]
    Garbled(String),
    #[error("cannot create a pseudo-terminal: {0}; run it on Linux or macOS")]
    Pty(String),
}
