//! Reading a recording: exactly the samples its header states. Bytes past them (appended, or a
//! block a killed `record` wrote before it updated the count) and a file shorter than its header
//! promises (a copy cut short) are refused with what they hold, never read as samples.

use std::cmp::Ordering;
use std::path::Path;

use shared::protocol::Sample;

use super::header::{self, Header};
use super::{RecordingError, RECORD_BYTES};

/// A recording as read back.
#[derive(Debug, Clone, PartialEq)]
pub struct Recording {
    /// Samples per second.
    pub rate_hz: u16,
    /// The serial of the board recorded; `None` in recordings written before it was kept.
    pub serial: Option<String>,
    /// Every complete record, in file order.
    pub samples: Vec<Sample>,
}

/// The recording at `path`: the samples its header states.
pub fn read_path(path: &Path) -> Result<Recording, RecordingError> {
    let name = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|source| RecordingError::Io { path: name.clone(), source })?;
    read_samples(&bytes, &name)
}

/// The recording in `bytes` (the file `name`): the samples its header states.
pub fn read_samples(bytes: &[u8], name: &str) -> Result<Recording, RecordingError> {
    let header =
        header::check(bytes).map_err(|reason| RecordingError::NotARecording { path: name.to_owned(), reason })?;
    let body = &bytes[header.bytes..];
    check_length(body.len() as u64, &header, name)?;
    let period_us = 1_000_000 / u64::from(header.rate_hz);
    let samples = body.chunks_exact(RECORD_BYTES).map(|record| decode(record, period_us)).collect();
    Ok(Recording { rate_hz: header.rate_hz, serial: header.serial, samples })
}

/// Refuses a body of other than the header's count of records, saying what it holds.
fn check_length(body_bytes: u64, header: &Header, name: &str) -> Result<(), RecordingError> {
    let (record, stated, path) = (RECORD_BYTES as u64, header.samples, name.to_owned());
    let stated_bytes = stated.saturating_mul(record);
    match body_bytes.cmp(&stated_bytes) {
        Ordering::Equal => Ok(()),
        Ordering::Less => Err(RecordingError::CutShort { path, held: body_bytes / record, stated }),
        Ordering::Greater => Err(RecordingError::PastStated {
            path,
            stated,
            extra_bytes: body_bytes - stated_bytes,
            keep_bytes: header.bytes as u64 + stated_bytes,
        }),
    }
}

/// Whether `bytes` (the file's first few) open a `.npy` file.
pub fn is_npy(bytes: &[u8]) -> bool {
    bytes.starts_with(header::MAGIC)
}

/// One record; its time is the chip's, the sample number times the sample period.
fn decode(record: &[u8], period_us: u64) -> Sample {
    let f32_at = |at: usize| f32::from_le_bytes([record[at], record[at + 1], record[at + 2], record[at + 3]]);
    let index = u32::from_le_bytes([record[0], record[1], record[2], record[3]]);
    Sample {
        index,
        time_us: u64::from(index) * period_us,
        accel_g: [f32_at(4), f32_at(8), f32_at(12)],
        gyro_dps: [f32_at(16), f32_at(20), f32_at(24)],
        temp_c: f32_at(28),
    }
}

#[cfg(test)]
mod tests {
    use super::super::{write::Recorder, BLOCK_SAMPLES};
    use super::*;

    fn sample(index: u32) -> Sample {
        let v = index as f32;
        Sample { index, time_us: u64::from(index) * 1000, accel_g: [v, -v, 1.0], gyro_dps: [0.5, v, 2.0], temp_c: 25.0 }
    }

    /// A finished recording of `total` samples, as `record` leaves it (written as `name`).
    fn recorded(name: &str, total: u32) -> Vec<u8> {
        let path = std::env::temp_dir().join(format!("accelcal-read-{name}-{}.npy", std::process::id()));
        let mut recorder = Recorder::create(&path, 1000, "53494D000000000000000017").unwrap();
        (0..total).for_each(|i| recorder.push(&sample(i)).unwrap());
        recorder.finish().unwrap();
        let bytes = std::fs::read(&path).unwrap();
        std::fs::remove_file(&path).unwrap();
        bytes
    }

    const TOTAL: u32 = 2 * BLOCK_SAMPLES as u32 + 500;

    #[test]
    fn a_recording_reads_exactly_the_samples_its_header_states() {
        let read = read_samples(&recorded("whole", TOTAL), "rec.npy").unwrap();
        assert_eq!(read.samples, (0..TOTAL).map(sample).collect::<Vec<_>>());
        assert_eq!((read.rate_hz, read.serial.as_deref()), (1000, Some("53494D000000000000000017")));
    }

    #[test]
    fn bytes_appended_past_the_stated_samples_are_refused_naming_them_and_how_to_keep_the_samples() {
        let mut bytes = recorded("appended", TOTAL);
        let stated_len = bytes.len();
        bytes.extend_from_slice(&[0; 4096]);
        let said = read_samples(&bytes, "rec.npy").map(|r| r.samples.len()).map_err(|e| e.to_string());
        let expected = format!("rec.npy holds 4096 bytes after the {TOTAL} samples its header states");
        assert!(matches!(&said, Err(said) if said.contains(&expected)), "{said:?}");
        let keep = format!("`truncate -s {stated_len} rec.npy`");
        assert!(matches!(&said, Err(said) if said.contains(&keep)), "{said:?}");
        // The way out it names: cut to that length, the file reads every sample it states.
        assert_eq!(read_samples(&bytes[..stated_len], "rec.npy").unwrap().samples.len(), TOTAL as usize);
    }

    #[test]
    fn a_file_shorter_than_its_header_promises_is_refused_naming_what_it_holds_and_what_was_promised() {
        let bytes = recorded("cut", TOTAL);
        // cut in the middle of the third block, mid-record; the header still says TOTAL.
        let cut = header::HEADER_BYTES + (2 * BLOCK_SAMPLES + 123) * RECORD_BYTES + 17;
        let said = read_samples(&bytes[..cut], "rec.npy").map(|r| r.samples.len()).map_err(|e| e.to_string());
        let expected =
            format!("it holds {} complete samples where its header promises {TOTAL}", 2 * BLOCK_SAMPLES + 123);
        assert!(matches!(&said, Err(said) if said.contains(&expected) && said.contains("cut short")), "{said:?}");
    }
}
