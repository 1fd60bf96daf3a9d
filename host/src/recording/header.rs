//! The `.npy` (version 1.0) header of a recording: magic, version, header length, and a Python
//! dict literal naming the record layout and the sample count.
//!
//! NOTE: the header is written with a fixed length, so that the count can be rewritten in place
//! after each block without moving the samples (format: numpy.lib.format, NEP 1).

/// The magic string that opens every `.npy` file.
pub const MAGIC: &[u8] = b"\x93NUMPY";

/// Bytes of the whole header, samples start here (a multiple of 64, as numpy aligns it).
pub const HEADER_BYTES: usize = 256;

/// The record layout as numpy's `descr`: one field per column, little-endian, packed.
pub const DESCR: &str = "[('seq', '<u4'), ('time_us', '<u8'), ('ax_g', '<f4'), ('ay_g', '<f4'), \
('az_g', '<f4'), ('gx_dps', '<f4'), ('gy_dps', '<f4'), ('gz_dps', '<f4'), ('temp_c', '<f4')]";

/// The header of a file holding `samples` records.
pub fn render(samples: u64) -> Vec<u8> {
    let dict = format!("{{'descr': {DESCR}, 'fortran_order': False, 'shape': ({samples},), }}");
    let text_len = HEADER_BYTES - MAGIC.len() - 4;
    let mut bytes = Vec::with_capacity(HEADER_BYTES);
    bytes.extend_from_slice(MAGIC);
    bytes.extend_from_slice(&[1, 0]);
    bytes.extend_from_slice(&(text_len as u16).to_le_bytes());
    bytes.extend_from_slice(format!("{dict:<width$}\n", width = text_len - 1).as_bytes());
    bytes
}

/// Checks that `bytes` open a recording of our layout; `Err` says what differs.
pub fn check(bytes: &[u8]) -> Result<(), String> {
    if bytes.len() < HEADER_BYTES || !bytes.starts_with(MAGIC) {
        return Err("it does not start with a .npy header".to_owned());
    }
    let text_len = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    if bytes[6] != 1 || text_len + 10 != HEADER_BYTES {
        return Err("its .npy header is not the one `accelcal record` writes".to_owned());
    }
    let text = String::from_utf8_lossy(&bytes[10..HEADER_BYTES]);
    if !text.contains(DESCR) || !text.contains("'fortran_order': False") {
        return Err(format!("its columns differ from {DESCR}"));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_header_keeps_its_length_and_names_the_count() {
        for samples in [0, 1, 3_600_000, u64::MAX] {
            let header = render(samples);
            assert_eq!(header.len(), HEADER_BYTES);
            assert!(String::from_utf8_lossy(&header).contains(&format!("'shape': ({samples},)")));
            assert_eq!(check(&header), Ok(()));
        }
    }
}
