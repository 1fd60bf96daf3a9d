//! `cargo xtask dist`: builds every board once and writes `dist/` (the interface is in DESIGN.md):
//! accelcal-blackpill-f411.bin, accelcal-blackpill-f401.bin, accelcal-pico.uf2, accelcal-pico2.uf2,
//! with each ELF file beside its image; fails when a board outgrows its flash or RAM budget.

mod elf;
mod uf2;

use std::path::{Path, PathBuf};
use std::process::Command;

use anyhow::{bail, Context, Result};

/// What the image of a board is flashed as.
#[derive(Debug, Clone, Copy)]
enum Format {
    /// A flat binary for the STM32's ROM DFU bootloader (`dfu-util`).
    Bin,
    /// A UF2 file for the boot ROM's USB drive, with the chip's family id.
    Uf2 { family: u32 },
}

/// One board: the crate, target and feature that build it, and its budget.
struct Board {
    name: &'static str,
    package: &'static str,
    binary: &'static str,
    target: &'static str,
    feature: &'static str,
    format: Format,
    flash_budget: u64,
    ram_budget: u64,
}

const KIB: u64 = 1024;

const BOARDS: [Board; 4] = [
    Board {
        name: "blackpill-f411",
        package: "board-blackpill",
        binary: "accelcal-blackpill",
        target: "thumbv7em-none-eabihf",
        feature: "f411",
        format: Format::Bin,
        flash_budget: 64 * KIB,
        ram_budget: 32 * KIB,
    },
    Board {
        name: "blackpill-f401",
        package: "board-blackpill",
        binary: "accelcal-blackpill",
        target: "thumbv7em-none-eabihf",
        feature: "f401",
        format: Format::Bin,
        flash_budget: 64 * KIB,
        ram_budget: 32 * KIB,
    },
    Board {
        name: "pico",
        package: "board-pico",
        binary: "accelcal-pico",
        target: "thumbv6m-none-eabi",
        feature: "pico",
        format: Format::Uf2 { family: uf2::RP2040_FAMILY },
        flash_budget: 64 * KIB,
        ram_budget: 32 * KIB,
    },
    Board {
        name: "pico2",
        package: "board-pico",
        binary: "accelcal-pico",
        target: "thumbv8m.main-none-eabihf",
        feature: "pico2",
        format: Format::Uf2 { family: uf2::RP2350_ARM_S_FAMILY },
        flash_budget: 64 * KIB,
        ram_budget: 32 * KIB,
    },
];

fn main() -> Result<()> {
    let task = std::env::args().nth(1);
    match task.as_deref() {
        Some("dist") => dist(),
        _ => bail!("usage: cargo xtask dist   (builds every board into dist/)"),
    }
}

/// Builds every board and writes its files into `dist/`; all budgets are checked before failing.
fn dist() -> Result<()> {
    let root = workspace_root();
    let dist = root.join("dist");
    std::fs::create_dir_all(&dist).with_context(|| format!("creating {}", dist.display()))?;
    let mut over_budget = Vec::new();
    for board in &BOARDS {
        eprintln!(
            "== {}: cargo build -p {} --target {} --features {}",
            board.name, board.package, board.target, board.feature
        );
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
    let status = Command::new(cargo)
        .current_dir(root)
        .args(["build", "--release", "-p", board.package, "--target", board.target, "--features", board.feature])
        .status()
        .context("running cargo build")?;
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
    std::fs::write(dist.join(format!("{stem}.elf")), &elf)?;
    let (base, image) = elf::flat_image(&elf)?;
    let (file, bytes) = match board.format {
        Format::Bin => (format!("{stem}.bin"), image),
        Format::Uf2 { family } => (format!("{stem}.uf2"), uf2::encode(&image, base, family)),
    };
    std::fs::write(dist.join(&file), bytes).with_context(|| format!("writing dist/{file}"))?;
    Ok(within)
}
