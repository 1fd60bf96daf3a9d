//! Reading a recording: every complete record after the header, whatever count the header says
//! (after a crash it may be stale, and the last record may be cut).

use std::path::Path;

use shared::protocol::Sample;

use super::{header, RecordingError, RECORD_BYTES};

/// The samples of the recording at `path`, up to the last complete record.
pub fn read_path(path: &Path) -> Result<Vec<Sample>, RecordingError> {
    let name = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|source| RecordingError::Io { path: name.clone(), source })?;
    read_samples(&bytes).map_err(|reason| RecordingError::NotARecording { path: name, reason })
}

/// The samples of a recording's bytes, up to the last complete record.
pub fn read_samples(bytes: &[u8]) -> Result<Vec<Sample>, String> {
    header::check(bytes)?;
    Ok(bytes[header::HEADER_BYTES..].chunks_exact(RECORD_BYTES).map(decode).collect())
}

/// Whether `bytes` (the file's first few) open a `.npy` file.
pub fn is_npy(bytes: &[u8]) -> bool {
    bytes.starts_with(header::MAGIC)
}

fn decode(record: &[u8]) -> Sample {
    let f32_at = |at: usize| f32::from_le_bytes([record[at], record[at + 1], record[at + 2], record[at + 3]]);
    let mut time = [0u8; 8];
    time.copy_from_slice(&record[4..12]);
    Sample {
        index: u32::from_le_bytes([record[0], record[1], record[2], record[3]]),
        time_us: u64::from_le_bytes(time),
        accel_g: [f32_at(12), f32_at(16), f32_at(20)],
        gyro_dps: [f32_at(24), f32_at(28), f32_at(32)],
        temp_c: f32_at(36),
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
        let mut recorder = Recorder::create(&path).unwrap();
        let total = 2 * BLOCK_SAMPLES as u32 + 500;
        (0..total).for_each(|i| recorder.push(&sample(i)).unwrap());
        recorder.finish().unwrap();
        let bytes = std::fs::read(&path).unwrap();
        std::fs::remove_file(&path).unwrap();
        assert_eq!(read_samples(&bytes).unwrap(), (0..total).map(sample).collect::<Vec<_>>());
        // cut in the middle of the third block, mid-record; the header still says `total`.
        let cut = header::HEADER_BYTES + (2 * BLOCK_SAMPLES + 123) * RECORD_BYTES + 17;
        let read = read_samples(&bytes[..cut]).unwrap();
        assert_eq!(read, (0..2 * BLOCK_SAMPLES as u32 + 123).map(sample).collect::<Vec<_>>());
    }
}
