//! The `.npy` (version 1.0) header of a recording: magic, version, header length, and a Python
//! dict literal naming the record layout, the sample rate and the sample count.
//!
//! NOTE: the header is written with a fixed length, so that the count can be rewritten in place
//! after each block without moving the samples (format: numpy.lib.format, NEP 1). numpy refuses
//! any key beside `descr`, `fortran_order` and `shape`, so the sample rate rides in the title of
//! the `seq` field, numpy's own place for a field's description (`dtype.fields['seq'][2]`).

/// The magic string that opens every `.npy` file.
pub const MAGIC: &[u8] = b"\x93NUMPY";

/// Bytes of the whole header, samples start here (a multiple of 64, as numpy aligns it).
pub const HEADER_BYTES: usize = 320;

/// The title of the `seq` field up to the rate.
const SEQ_TITLE: &str = "sample number; samples per second: ";

/// The record layout as numpy's `descr` for a recording at `rate_hz`.
// NOTE: the columns after `seq` are f32, little-endian, packed: the sample time is `seq` over the rate.
pub fn descr(rate_hz: u16) -> String {
    let columns: Vec<String> = super::SAMPLE_COLUMNS.iter().map(|c| format!("('{c}', '<f4')")).collect();
    format!("[(('{SEQ_TITLE}{rate_hz}; time_s = seq / {rate_hz}', 'seq'), '<u4'), {}]", columns.join(", "))
}

/// The header of a file holding `samples` records taken at `rate_hz`.
pub fn render(samples: u64, rate_hz: u16) -> Vec<u8> {
    let dict = format!("{{'descr': {}, 'fortran_order': False, 'shape': ({samples},), }}", descr(rate_hz));
    let text_len = HEADER_BYTES - MAGIC.len() - 4;
    let mut bytes = Vec::with_capacity(HEADER_BYTES);
    bytes.extend_from_slice(MAGIC);
    bytes.extend_from_slice(&[1, 0]);
    bytes.extend_from_slice(&(text_len as u16).to_le_bytes());
    bytes.extend_from_slice(format!("{dict:<width$}\n", width = text_len - 1).as_bytes());
    bytes
}

/// The sample rate in Hz of a recording of our layout that `bytes` open; `Err` says what differs.
pub fn check(bytes: &[u8]) -> Result<u16, String> {
    if bytes.len() < HEADER_BYTES || !bytes.starts_with(MAGIC) {
        return Err("it does not start with a .npy header".to_owned());
    }
    let text_len = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    if bytes[6] != 1 || text_len + 10 != HEADER_BYTES {
        return Err("its .npy header is not the one `accelcal record` writes".to_owned());
    }
    let text = String::from_utf8_lossy(&bytes[10..HEADER_BYTES]);
    let rate_hz = rate_in(&text).ok_or_else(|| format!("its columns differ from {}", descr(1000)))?;
    if !text.contains(&descr(rate_hz)) || !text.contains("'fortran_order': False") {
        return Err(format!("its columns differ from {}", descr(rate_hz)));
    }
    Ok(rate_hz)
}

/// The sample rate the `seq` title in a header's text names.
fn rate_in(text: &str) -> Option<u16> {
    let after = &text[text.find(SEQ_TITLE)? + SEQ_TITLE.len()..];
    after[..after.find(';')?].parse().ok().filter(|&rate| rate > 0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_header_keeps_its_length_and_names_the_count_and_the_rate() {
        for (samples, rate_hz) in [(0, 1), (1, 1000), (3_600_000, 250), (u64::MAX, 1000)] {
            let header = render(samples, rate_hz);
            assert_eq!(header.len(), HEADER_BYTES);
            assert!(String::from_utf8_lossy(&header).contains(&format!("'shape': ({samples},)")));
            assert_eq!(check(&header), Ok(rate_hz));
        }
    }

    #[test]
    fn the_columns_are_those_every_recording_names_so_older_files_still_read() {
        let written_since_the_start = "[(('sample number; samples per second: 100; time_s = seq / 100', 'seq'), '<u4'), \
            ('ax_g', '<f4'), ('ay_g', '<f4'), ('az_g', '<f4'), ('gx_dps', '<f4'), ('gy_dps', '<f4'), ('gz_dps', '<f4'), \
            ('temp_c', '<f4')]";
        assert_eq!(descr(100), written_since_the_start);
    }
}
