//! Reading a recording: every complete record after the header, whatever count the header says
//! (after a crash it may be stale, and the last record may be cut).

use std::path::Path;

use shared::protocol::Sample;

use super::{header, RecordingError, RECORD_BYTES};

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

/// The recording at `path`, up to the last complete record.
pub fn read_path(path: &Path) -> Result<Recording, RecordingError> {
    let name = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|source| RecordingError::Io { path: name.clone(), source })?;
    read_samples(&bytes).map_err(|reason| RecordingError::NotARecording { path: name, reason })
}

/// The recording in `bytes`, up to the last complete record.
pub fn read_samples(bytes: &[u8]) -> Result<Recording, String> {
    let header = header::check(bytes)?;
    let period_us = 1_000_000 / u64::from(header.rate_hz);
    let records = bytes[header.bytes..].chunks_exact(RECORD_BYTES);
    let samples = records.map(|record| decode(record, period_us)).collect();
    Ok(Recording { rate_hz: header.rate_hz, serial: header.serial, samples })
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

    #[test]
    fn a_file_cut_mid_block_reads_up_to_the_last_complete_block_intact() {
        let path = std::env::temp_dir().join(format!("accelcal-cut-{}.npy", std::process::id()));
        let mut recorder = Recorder::create(&path, 1000, "53494D000000000000000017").unwrap();
        let total = 2 * BLOCK_SAMPLES as u32 + 500;
        (0..total).for_each(|i| recorder.push(&sample(i)).unwrap());
        recorder.finish().unwrap();
        let bytes = std::fs::read(&path).unwrap();
        std::fs::remove_file(&path).unwrap();
        assert_eq!(read_samples(&bytes).unwrap().samples, (0..total).map(sample).collect::<Vec<_>>());
        assert_eq!(read_samples(&bytes).unwrap().rate_hz, 1000);
        assert_eq!(read_samples(&bytes).unwrap().serial.as_deref(), Some("53494D000000000000000017"));
        // cut in the middle of the third block, mid-record; the header still says `total`.
        let cut = header::HEADER_BYTES + (2 * BLOCK_SAMPLES + 123) * RECORD_BYTES + 17;
        let read = read_samples(&bytes[..cut]).unwrap().samples;
        assert_eq!(read, (0..2 * BLOCK_SAMPLES as u32 + 123).map(sample).collect::<Vec<_>>());
    }
}
