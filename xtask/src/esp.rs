//! The ESP32 image: espflash (from crates.io, `cargo install --locked espflash`) merges the program
//! with the ESP-IDF second-stage bootloader it ships and our partition table into one file that a
//! browser flasher or `espflash write-bin 0x0` writes at the start of flash.
//!
//! NOTE: not written here as the UF2 is: the merged image must carry Espressif's bootloader, a
//! binary we may not copy into the repository, and espflash is the tool that carries it.

use std::path::Path;
use std::process::Command;

use anyhow::{bail, Context, Result};

/// Where the bootloader espflash ships reads the partition table (ESP-IDF's default
/// CONFIG_PARTITION_TABLE_OFFSET). NOTE: espflash's own guess is the first partition's offset less
/// 0x1000 (0xF000 for our table), where that bootloader would find nothing.
const PARTITION_TABLE_OFFSET: &str = "0x8000";

/// Writes the merged image of the ELF file at `elf` for `chip` with the partition table `partitions`
/// (ESP-IDF CSV) to `file`, ending where the program ends (the calibration partition is not written).
pub fn merged_image(elf: &Path, chip: &str, partitions: &Path, file: &Path) -> Result<()> {
    let status = Command::new("espflash")
        .args(["save-image", "--skip-update-check", "--chip", chip, "--merge", "--skip-padding"])
        .args(["--partition-table-offset", PARTITION_TABLE_OFFSET, "--partition-table"])
        .args([partitions, elf, file])
        .status()
        .context("running espflash: install it with `cargo install --locked espflash` (docs/boards.md)")?;
    if !status.success() {
        bail!("espflash save-image failed for {}", elf.display());
    }
    Ok(())
}
