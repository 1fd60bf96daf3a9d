//! What `cargo xtask dist` needs before it builds anything, checked first: a board target rustup has
//! not installed, flip-link (the Black Pill's linker) or espflash (the ESP32-C3's image) missing is
//! said at once, all of it with the commands that install it, instead of failing after half an hour
//! of building the boards that come first (issue 40).

use std::path::{Path, PathBuf};

use crate::{Board, Format};

/// A tool or target the chosen boards need, and the command that installs it.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
pub struct Need {
    /// What is needed, as a person names it.
    pub what: String,
    /// The command that installs it.
    pub install: String,
}

/// What `boards` need that `present` (a target or program name -> installed?) says is missing, each once.
pub fn missing(boards: &[&Board], present: impl Fn(&str) -> bool) -> Vec<Need> {
    let mut needs: Vec<Need> = boards.iter().flat_map(|board| needs_of(board)).filter(|n| !present(&n.what)).collect();
    needs.sort();
    needs.dedup();
    needs
}

/// Everything one board's build needs outside the workspace.
fn needs_of(board: &Board) -> Vec<Need> {
    let mut needs =
        vec![Need { what: board.target.to_owned(), install: format!("rustup target add {}", board.target) }];
    // NOTE: .cargo/config.toml names flip-link as this target's linker.
    if board.target == "thumbv7em-none-eabihf" {
        needs.push(Need { what: "flip-link".into(), install: "cargo install --locked flip-link".into() });
    }
    if let Format::EspMerged { .. } = board.format {
        // NOTE: the version CI pins, so that the bootloader it ships changes only on purpose (.ci/run).
        let install = "cargo install --locked espflash --version 4.7.0".into();
        needs.push(Need { what: "espflash".into(), install });
    }
    needs
}

/// The message that lists what is missing and how to install all of it, or `None` when nothing is.
pub fn refusal(missing: &[Need]) -> Option<String> {
    if missing.is_empty() {
        return None;
    }
    let what: Vec<&str> = missing.iter().map(|n| n.what.as_str()).collect();
    let commands: Vec<&str> = missing.iter().map(|n| n.install.as_str()).collect();
    Some(format!(
        "the boards need what this machine lacks: {}; nothing was built. Install it, then run `cargo xtask dist` \
         again:\n  {}\n(espflash's serial support needs libudev: `apt-get install libudev-dev pkg-config` on Debian)",
        what.join(", "),
        commands.join("\n  ")
    ))
}

/// Whether `name` (a rustup target or a program) is installed on this machine.
pub fn installed(name: &str, sysroot: Option<&Path>) -> bool {
    if name.contains("-none") {
        return sysroot.is_some_and(|root| root.join("lib/rustlib").join(name).is_dir());
    }
    on_path(name)
}

/// rustc's sysroot, where rustup puts each target's standard library.
pub fn sysroot() -> Option<PathBuf> {
    let output = std::process::Command::new("rustc").args(["--print", "sysroot"]).output().ok()?;
    output.status.success().then(|| PathBuf::from(String::from_utf8_lossy(&output.stdout).trim()))
}

fn on_path(program: &str) -> bool {
    let paths = std::env::var_os("PATH").unwrap_or_default();
    std::env::split_paths(&paths).any(|dir| dir.join(program).is_file())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::BOARDS;

    #[test]
    fn every_missing_need_of_every_board_is_said_at_once_with_its_install_command() {
        let all: Vec<&Board> = BOARDS.iter().collect();
        let nothing = missing(&all, |_| false);
        let names: Vec<&str> = nothing.iter().map(|n| n.what.as_str()).collect();
        assert_eq!(
            names,
            [
                "espflash",
                "flip-link",
                "riscv32imc-unknown-none-elf",
                "thumbv6m-none-eabi",
                "thumbv7em-none-eabihf",
                "thumbv8m.main-none-eabihf"
            ]
        );
        let message = refusal(&nothing).expect("a refusal");
        assert!(message.contains("rustup target add thumbv6m-none-eabi"), "{message}");
        assert!(message.contains("cargo install --locked espflash --version 4.7.0"), "{message}");
        assert!(message.contains("nothing was built"), "{message}");
        assert_eq!(refusal(&missing(&all, |_| true)), None);
    }

    #[test]
    fn a_board_asks_only_for_what_it_needs() {
        let pico: Vec<&Board> = BOARDS.iter().filter(|b| b.name == "pico").collect();
        let needs = missing(&pico, |_| false);
        assert_eq!(needs.iter().map(|n| n.what.as_str()).collect::<Vec<_>>(), ["thumbv6m-none-eabi"]);
        let esp: Vec<&Board> = BOARDS.iter().filter(|b| b.name == "esp32c3").collect();
        let needs = missing(&esp, |name| name != "espflash");
        assert_eq!(needs.iter().map(|n| n.what.as_str()).collect::<Vec<_>>(), ["espflash"]);
    }
}
