//! `cargo xtask dist`: builds every board once and writes `dist/` (the interface is in DESIGN.md):
//! accelcal-blackpill-f411.bin, accelcal-blackpill-f401.bin, accelcal-pico.uf2, accelcal-pico2.uf2,
//! accelcal-esp32c3.bin, with each ELF file beside its image; fails when a board outgrows its flash
//! or RAM budget. `cargo xtask web`: the web page into `target/web` (web.rs, docs/web.md).

mod elf;
mod esp;
mod preflight;
mod uf2;
mod web;

use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};

use anyhow::{bail, Context, Result};

/// What the image of a board is flashed as.
#[derive(Debug, Clone, Copy)]
enum Format {
    /// A flat binary for the STM32's ROM DFU bootloader (`dfu-util`).
    Bin,
    /// A UF2 file for the boot ROM's USB drive, with the chip's family id.
    Uf2 { family: u32 },
    /// An ESP32 image merged with its bootloader and partition table (`espflash save-image --merge`).
    EspMerged { chip: &'static str, partitions: &'static str },
}

/// One board: the crate, target and feature that build it, and its budget.
struct Board {
    name: &'static str,
    package: &'static str,
    binary: &'static str,
    target: &'static str,
    /// The board crate's feature that picks the chip, when the crate builds several.
    feature: Option<&'static str>,
    format: Format,
    flash_budget: u64,
    ram_budget: u64,
}

const KIB: u64 = 1024;

const BOARDS: [Board; 5] = [
    Board {
        name: "blackpill-f411",
        package: "board-blackpill",
        binary: "accelcal-blackpill",
        target: "thumbv7em-none-eabihf",
        feature: Some("f411"),
        format: Format::Bin,
        flash_budget: 64 * KIB,
        ram_budget: 32 * KIB,
    },
    Board {
        name: "blackpill-f401",
        package: "board-blackpill",
        binary: "accelcal-blackpill",
        target: "thumbv7em-none-eabihf",
        feature: Some("f401"),
        format: Format::Bin,
        flash_budget: 64 * KIB,
        ram_budget: 32 * KIB,
    },
    Board {
        name: "pico",
        package: "board-pico",
        binary: "accelcal-pico",
        target: "thumbv6m-none-eabi",
        feature: Some("pico"),
        format: Format::Uf2 { family: uf2::RP2040_FAMILY },
        flash_budget: 64 * KIB,
        ram_budget: 32 * KIB,
    },
    Board {
        name: "pico2",
        package: "board-pico",
        binary: "accelcal-pico",
        target: "thumbv8m.main-none-eabihf",
        feature: Some("pico2"),
        format: Format::Uf2 { family: uf2::RP2350_ARM_S_FAMILY },
        flash_budget: 64 * KIB,
        ram_budget: 32 * KIB,
    },
    Board {
        name: "esp32c3",
        package: "board-esp32c3",
        binary: "accelcal-esp32c3",
        target: "riscv32imc-unknown-none-elf",
        feature: None,
        format: Format::EspMerged { chip: "esp32c3", partitions: "boards/esp32c3/partitions.csv" },
        flash_budget: 128 * KIB,
        ram_budget: 32 * KIB,
    },
];

// NOTE: the error is printed here, not returned from main: anyhow prints a backtrace under
// RUST_BACKTRACE=1, and a missing tool or a board over budget is a message, not a crash (issue 40).
fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error:#}");
            ExitCode::FAILURE
        }
    }
}

fn run() -> Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.split_first() {
        Some((task, names)) if task == "dist" => dist(&chosen(names)?),
        Some((task, [])) if task == "web" => web::build(&workspace_root()).map(|_| ()),
        _ => bail!(
            "usage: cargo xtask dist [BOARD...]   (builds every board, or the ones named, into dist/)\n       \
             cargo xtask web              (builds the web page into target/web; docs/web.md)"
        ),
    }
}

/// The boards `names` picks (every board when it names none); an unknown name lists the known ones.
fn chosen(names: &[String]) -> Result<Vec<&'static Board>> {
    if names.is_empty() {
        return Ok(BOARDS.iter().collect());
    }
    let known = || BOARDS.iter().map(|b| b.name).collect::<Vec<_>>().join(", ");
    let find = |name: &String| BOARDS.iter().find(|b| b.name == name.as_str());
    names.iter().map(|name| find(name).with_context(|| format!("no board {name:?}; the boards: {}", known()))).collect()
}

/// Builds the boards and writes their files into `dist/`; all budgets are checked before failing.
fn dist(boards: &[&Board]) -> Result<()> {
    let sysroot = preflight::sysroot();
    let missing = preflight::missing(boards, |name| preflight::installed(name, sysroot.as_deref()));
    if let Some(refusal) = preflight::refusal(&missing) {
        bail!(refusal);
    }
    let root = workspace_root();
    let dist = root.join("dist");
    std::fs::create_dir_all(&dist).with_context(|| format!("creating {}", dist.display()))?;
    let mut over_budget = Vec::new();
    for board in boards {
        let features = board.feature.map(|f| format!(" --features {f}")).unwrap_or_default();
        eprintln!("== {}: cargo build -p {} --target {}{features}", board.name, board.package, board.target);
        build(&root, board)?;
        if !write_board(&root, &dist, board)? {
            over_budget.push(board.name);
        }
    }
    if !over_budget.is_empty() {
        bail!("over budget: {}", over_budget.join(", "));
    }
    Ok(())
}

fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("xtask sits in the workspace root").to_path_buf()
}

fn build(root: &Path, board: &Board) -> Result<()> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let mut command = Command::new(cargo);
    command.current_dir(root).args(["build", "--release", "-p", board.package, "--target", board.target]);
    if let Some(feature) = board.feature {
        command.args(["--features", feature]);
    }
    let status = command.status().context("running cargo build")?;
    if !status.success() {
        bail!("the {} build failed", board.name);
    }
    Ok(())
}

/// Copies the ELF and writes the image of one board; whether it is within its budget.
fn write_board(root: &Path, dist: &Path, board: &Board) -> Result<bool> {
    let built = root.join("target").join(board.target).join("release").join(board.binary);
    let elf = std::fs::read(&built).with_context(|| format!("reading {}", built.display()))?;
    let footprint = elf::footprint(&elf)?;
    let within = footprint.flash <= board.flash_budget && footprint.ram <= board.ram_budget;
    eprintln!(
        "{}: flash {} bytes of {}, static RAM {} bytes of {}{}",
        board.name,
        footprint.flash,
        board.flash_budget,
        footprint.ram,
        board.ram_budget,
        if within { "" } else { "  OVER BUDGET" }
    );
    let stem = format!("accelcal-{}", board.name);
    let elf_path = dist.join(format!("{stem}.elf"));
    std::fs::write(&elf_path, &elf)?;
    let file = dist.join(format!("{stem}.{}", board.format.extension()));
    write_image(board.format, root, &elf_path, &file).with_context(|| format!("writing {}", file.display()))?;
    Ok(within)
}

impl Format {
    fn extension(self) -> &'static str {
        match self {
            Format::Bin | Format::EspMerged { .. } => "bin",
            Format::Uf2 { .. } => "uf2",
        }
    }
}

/// Writes the image of the ELF file at `elf_path` to `file`, as `format` says.
fn write_image(format: Format, root: &Path, elf_path: &Path, file: &Path) -> Result<()> {
    let elf = std::fs::read(elf_path)?;
    match format {
        Format::Bin => std::fs::write(file, elf::flat_image(&elf)?.1)?,
        Format::Uf2 { family } => {
            let (base, image) = elf::flat_image(&elf)?;
            std::fs::write(file, uf2::encode(&image, base, family))?;
        }
        Format::EspMerged { chip, partitions } => esp::merged_image(elf_path, chip, &root.join(partitions), file)?,
    }
    Ok(())
}
