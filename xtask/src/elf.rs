//! What a board ELF weighs (flash and static RAM, by section) and its flat image (load segments at
//! their physical addresses, gaps as erased flash).

use anyhow::{bail, Context, Result};
use object::elf::PT_LOAD;
use object::read::elf::{ElfFile32, ProgramHeader};
use object::{Endianness, Object, ObjectSection};

/// Flash and static RAM of a board image, in bytes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Footprint {
    pub flash: u64,
    pub ram: u64,
}

/// Flash and static RAM by section: code, read-only data, the boot blocks and the
/// initial values of .data in flash; .data, .bss and .uninit in RAM. The ESP32-C3's trap vectors,
/// its code run from RAM (.rwtext, copied from flash at boot) and its application descriptor count
/// as flash.
pub fn footprint(elf: &[u8]) -> Result<Footprint> {
    let file = object::File::parse(elf).context("not an ELF file")?;
    let mut footprint = Footprint { flash: 0, ram: 0 };
    for section in file.sections() {
        let size = section.size();
        match section.name().unwrap_or("") {
            ".vector_table" | ".text" | ".rodata" | ".boot2" | ".start_block" | ".rwtext" | ".trap"
            | ".flash.appdesc" => footprint.flash += size,
            ".data" => {
                footprint.flash += size;
                footprint.ram += size;
            }
            ".bss" | ".uninit" | ".noinit" => footprint.ram += size,
            _ => {}
        }
    }
    Ok(footprint)
}

/// The bytes flash must hold from the lowest load address on, and that address. Segments are placed
/// at their physical (load) address: .data's initial values live in flash though it runs from RAM.
pub fn flat_image(elf: &[u8]) -> Result<(u32, Vec<u8>)> {
    let file = ElfFile32::<Endianness>::parse(elf).context("not a 32-bit ELF file")?;
    let endian = file.endian();
    let mut pieces = Vec::new();
    for header in file.elf_program_headers() {
        let data = header.data(endian, elf).map_err(|_| anyhow::anyhow!("unreadable load segment"))?;
        if header.p_type(endian) == PT_LOAD && !data.is_empty() {
            pieces.push((header.p_paddr(endian), data));
        }
    }
    let Some(base) = pieces.iter().map(|&(address, _)| address).min() else {
        bail!("the ELF file has nothing to load");
    };
    let end = pieces.iter().map(|&(address, data)| address + data.len() as u32).max().unwrap_or(base);
    let mut image = vec![0xFF; (end - base) as usize];
    for (address, data) in pieces {
        let at = (address - base) as usize;
        image[at..at + data.len()].copy_from_slice(data);
    }
    Ok((base, image))
}
