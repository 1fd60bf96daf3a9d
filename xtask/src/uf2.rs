//! UF2, the format the RP2040's and RP2350's boot ROMs take by drag and drop onto their USB drive.
//!
//! NOTE: written here rather than installing elf2uf2-rs: the format is a dozen lines (the UF2
//! specification, github.com/microsoft/uf2, README "File format"); `cargo install --locked elf2uf2-rs`
//! (2.2.0) fails on a machine without libudev's development files (it links a serial port crate to
//! deploy to boards), so CI would need system packages for a conversion this small.

/// Family id of RP2040 images (UF2 specification, utils/uf2families.json, "rp2040").
pub const RP2040_FAMILY: u32 = 0xE48B_FF56;
/// Family id of RP2350 Arm Secure images (same list, "rp2350-arm-s"; RP2350 datasheet 5.5.3).
pub const RP2350_ARM_S_FAMILY: u32 = 0xE48B_FF59;

const MAGIC_START0: u32 = 0x0A32_4655;
const MAGIC_START1: u32 = 0x9E5D_5157;
const MAGIC_END: u32 = 0x0AB1_6F30;
/// Flag: the family id field is present.
const FLAG_FAMILY_ID_PRESENT: u32 = 0x0000_2000;
/// Bytes of each block's payload: the flash page size of both chips (the boot ROMs take 256).
pub const PAYLOAD_LEN: usize = 256;
/// Bytes of a block.
pub const BLOCK_LEN: usize = 512;
/// Bytes of the data field of a block (the payload, then zeros).
const DATA_FIELD_LEN: usize = 476;

/// The UF2 file of `image` to be written at `base` (a multiple of 256), for the chip `family`.
pub fn encode(image: &[u8], base: u32, family: u32) -> Vec<u8> {
    let count = image.len().div_ceil(PAYLOAD_LEN) as u32;
    let mut out = Vec::with_capacity(count as usize * BLOCK_LEN);
    for (number, chunk) in image.chunks(PAYLOAD_LEN).enumerate() {
        let address = base + (number * PAYLOAD_LEN) as u32;
        let header = [
            MAGIC_START0,
            MAGIC_START1,
            FLAG_FAMILY_ID_PRESENT,
            address,
            PAYLOAD_LEN as u32,
            number as u32,
            count,
            family,
        ];
        for word in header {
            out.extend_from_slice(&word.to_le_bytes());
        }
        let mut data = [0u8; DATA_FIELD_LEN];
        // NOTE: a short last chunk is padded with 0xFF, erased flash, to a whole page.
        data[..PAYLOAD_LEN].fill(0xFF);
        data[..chunk.len()].copy_from_slice(chunk);
        out.extend_from_slice(&data);
        out.extend_from_slice(&MAGIC_END.to_le_bytes());
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn word(file: &[u8], block: usize, index: usize) -> u32 {
        let at = block * BLOCK_LEN + 4 * index;
        u32::from_le_bytes(file[at..at + 4].try_into().unwrap())
    }

    #[test]
    fn each_256_bytes_become_one_512_byte_block_at_its_address_with_the_family_id() {
        let image: Vec<u8> = (0..600u32).map(|i| i as u8).collect();
        let file = encode(&image, 0x1000_0000, RP2350_ARM_S_FAMILY);
        assert_eq!(file.len(), 3 * 512);
        for block in 0..3 {
            // Magic numbers, flags, address, size, number, count, family (UF2 README, "File format").
            assert_eq!(word(&file, block, 0), 0x0A32_4655);
            assert_eq!(word(&file, block, 1), 0x9E5D_5157);
            assert_eq!(word(&file, block, 2), 0x2000);
            assert_eq!(word(&file, block, 3), 0x1000_0000 + 256 * block as u32);
            assert_eq!((word(&file, block, 4), word(&file, block, 5), word(&file, block, 6)), (256, block as u32, 3));
            assert_eq!(word(&file, block, 7), 0xE48B_FF59);
            assert_eq!(word(&file, block, 127), 0x0AB1_6F30);
        }
        assert_eq!(&file[512 + 32..512 + 32 + 256], &image[256..512]);
        let last = &file[1024 + 32..1024 + 32 + 256];
        assert_eq!(&last[..88], &image[512..]);
        assert!(last[88..].iter().all(|&b| b == 0xFF), "the short page is padded with erased flash");
    }
}
