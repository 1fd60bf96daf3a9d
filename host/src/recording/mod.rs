//! Recordings: long raw sample series in a NumPy `.npy` file of one structured record per sample,
//! written as they stream and readable up to the last complete block after a crash
//! (`np.load("rec.npy")` in Python; [`read::read_path`] here).

pub mod header;
pub mod read;
pub mod write;

pub use read::{read_path, read_samples};
pub use write::Recorder;

/// Bytes of one record: `seq` u32, `time_us` u64, six f32 axes, `temp_c` f32, packed.
pub const RECORD_BYTES: usize = 4 + 8 + 7 * 4;

/// Samples written per block; the header's count is brought up to date after each block, so a
/// crash loses at most this many (one second at 1 kHz).
pub const BLOCK_SAMPLES: usize = 1000;

/// Why a recording cannot be written or read.
#[derive(Debug, thiserror::Error)]
pub enum RecordingError {
    #[error("{path}: {source}; check the path and that the folder is writable")]
    Io { path: String, source: std::io::Error },
    #[error("{path} is not an accelcal recording: {reason}")]
    NotARecording { path: String, reason: String },
}
