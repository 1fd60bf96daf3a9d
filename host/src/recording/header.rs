//! The `.npy` (version 1.0) header of a recording: magic, version, header length, and a Python
//! dict literal naming the record layout, the sample rate, the board's serial and the sample count.
//!
//! NOTE: the header is written with a fixed length, so that the count can be rewritten in place
//! after each block without moving the samples (format: numpy.lib.format, NEP 1). numpy refuses
//! any key beside `descr`, `fortran_order` and `shape`, so the sample rate and the board ride in
//! the title of the `seq` field, numpy's own place for a field's description
//! (`dtype.fields['seq'][2]`).

/// The magic string that opens every `.npy` file.
pub const MAGIC: &[u8] = b"\x93NUMPY";

/// Bytes of the whole header, samples start here (a multiple of 64, as numpy aligns it).
pub const HEADER_BYTES: usize = 384;
/// Bytes of the header of recordings written before the board was named in it (still read).
const UNNAMED_HEADER_BYTES: usize = 320;

/// The title of the `seq` field up to the rate.
const SEQ_TITLE: &str = "sample number; samples per second: ";
/// Before the board's serial in the title.
const BOARD_TITLE: &str = "; board ";

/// What a recording's header says of it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Header {
    /// Samples per second.
    pub rate_hz: u16,
    /// The serial of the board recorded (24 hexadecimal digits); `None` in recordings written
    /// before it was kept.
    pub serial: Option<String>,
    /// Bytes of the header: the samples start here.
    pub bytes: usize,
    /// The samples its `shape` states: exactly those follow the header.
    pub samples: u64,
}

/// The record layout as numpy's `descr` for a recording at `rate_hz` of the board `serial`.
pub fn descr(rate_hz: u16, serial: Option<&str>) -> String {
    let board = serial.map(|serial| format!("{BOARD_TITLE}{serial}")).unwrap_or_default();
    // NOTE: the columns after `seq` are f32, little-endian, packed: the sample time is `seq` over the rate.
    let columns: Vec<String> = super::SAMPLE_COLUMNS.iter().map(|c| format!("('{c}', '<f4')")).collect();
    format!("[(('{SEQ_TITLE}{rate_hz}{board}; time_s = seq / {rate_hz}', 'seq'), '<u4'), {}]", columns.join(", "))
}

/// The header of a file holding `samples` records taken at `rate_hz` on the board `serial`.
pub fn render(samples: u64, rate_hz: u16, serial: &str) -> Vec<u8> {
    let dict =
        format!("{{'descr': {}, 'fortran_order': False, 'shape': ({samples},), }}", descr(rate_hz, Some(serial)));
    let text_len = HEADER_BYTES - MAGIC.len() - 4;
    let mut bytes = Vec::with_capacity(HEADER_BYTES);
    bytes.extend_from_slice(MAGIC);
    bytes.extend_from_slice(&[1, 0]);
    bytes.extend_from_slice(&(text_len as u16).to_le_bytes());
    bytes.extend_from_slice(format!("{dict:<width$}\n", width = text_len - 1).as_bytes());
    bytes
}

/// What the header of a recording of our layout that `bytes` open says; `Err` says what differs.
pub fn check(bytes: &[u8]) -> Result<Header, String> {
    if bytes.len() < UNNAMED_HEADER_BYTES || !bytes.starts_with(MAGIC) {
        return Err("it does not start with a .npy header".to_owned());
    }
    let header_bytes = usize::from(u16::from_le_bytes([bytes[8], bytes[9]])) + MAGIC.len() + 4;
    if bytes[6] != 1 || ![HEADER_BYTES, UNNAMED_HEADER_BYTES].contains(&header_bytes) || bytes.len() < header_bytes {
        return Err("its .npy header is not the one `accelcal record` writes".to_owned());
    }
    let text = String::from_utf8_lossy(&bytes[10..header_bytes]);
    let differs = |rate_hz, serial| format!("its columns differ from {}", descr(rate_hz, serial));
    let rate_hz = rate_in(&text).ok_or_else(|| differs(1000, None))?;
    let serial = serial_in(&text);
    if !text.contains(&descr(rate_hz, serial.as_deref())) || !text.contains("'fortran_order': False") {
        return Err(differs(rate_hz, serial.as_deref()));
    }
    let samples = samples_in(&text).ok_or("its .npy header states no sample count (`'shape': (N,)`)")?;
    Ok(Header { rate_hz, serial, bytes: header_bytes, samples })
}

/// The sample count a header's `shape` states.
fn samples_in(text: &str) -> Option<u64> {
    const SHAPE: &str = "'shape': (";
    let after = &text[text.find(SHAPE)? + SHAPE.len()..];
    after[..after.find(",)")?].parse().ok()
}

/// The sample rate the `seq` title in a header's text names.
fn rate_in(text: &str) -> Option<u16> {
    let after = &text[text.find(SEQ_TITLE)? + SEQ_TITLE.len()..];
    after[..after.find(';')?].parse().ok().filter(|&rate| rate > 0)
}

/// The board's serial the `seq` title in a header's text names, if it names one.
fn serial_in(text: &str) -> Option<String> {
    let after = &text[text.find(BOARD_TITLE)? + BOARD_TITLE.len()..];
    Some(after[..after.find(';')?].to_owned())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_header_keeps_its_length_and_names_the_count_the_rate_and_the_board() {
        for (samples, rate_hz) in [(0, 1), (1, 1000), (3_600_000, 250), (u64::MAX, 1000)] {
            let header = render(samples, rate_hz, SERIAL);
            assert_eq!(header.len(), HEADER_BYTES);
            assert!(String::from_utf8_lossy(&header).contains(&format!("'shape': ({samples},)")));
            let read = Header { rate_hz, serial: Some(SERIAL.to_owned()), bytes: HEADER_BYTES, samples };
            assert_eq!(check(&header), Ok(read));
        }
    }

    #[test]
    fn a_recording_written_before_the_board_was_named_is_read_without_one() {
        let dict = format!("{{'descr': {}, 'fortran_order': False, 'shape': (5,), }}", descr(100, None));
        let text_len = UNNAMED_HEADER_BYTES - 10;
        let mut bytes = [MAGIC, &[1, 0], &(text_len as u16).to_le_bytes()].concat();
        bytes.extend_from_slice(format!("{dict:<width$}\n", width = text_len - 1).as_bytes());
        let read = Header { rate_hz: 100, serial: None, bytes: UNNAMED_HEADER_BYTES, samples: 5 };
        assert_eq!(check(&bytes), Ok(read));
    }

    const SERIAL: &str = "53494D000000000000000017";

    #[test]
    fn the_columns_are_those_every_recording_names_so_older_files_still_read() {
        let written_since_the_start = "[(('sample number; samples per second: 100; time_s = seq / 100', 'seq'), '<u4'), \
            ('ax_g', '<f4'), ('ay_g', '<f4'), ('az_g', '<f4'), ('gx_dps', '<f4'), ('gy_dps', '<f4'), ('gz_dps', '<f4'), \
            ('temp_c', '<f4')]";
        assert_eq!(descr(100, None), written_since_the_start);
    }
}
