//! Recordings: long raw sample series in a NumPy `.npy` file of one structured record per sample,
//! written as they stream, the header's count brought up to date after each block
//! (`np.load("rec.npy")` in Python; [`read::read_path`] here, exactly the samples the header states).
//! `accelcal stream`'s CSV rows are here too ([`csv`]).

pub mod csv;
pub mod header;
pub mod read;
pub mod record;
pub mod write;

pub use read::{read_path, read_samples, Recording};
pub use write::Recorder;

/// Bytes of one record: `seq` u32, six f32 axes, `temp_c` f32, packed.
///
/// NOTE: no time column: the chip stamps a sample with its FIFO count times the sample period
/// (firmware device/jobs.rs), so the time is `seq` over the rate the header names; a u64 of it
/// took 8 of 40 bytes. 32 bytes is 115.2 MB an hour at 1 kHz.
pub const RECORD_BYTES: usize = 4 + 7 * 4;

/// The columns of a sample, in a recording after `seq` and in `accelcal stream`'s CSV after
/// [`STREAM_COLUMNS`]: the accelerometer in g, the gyro in deg/s, the die temperature. The one list
/// the `.npy` header, `accelcal stream` and the noise analysis's reader take.
pub const SAMPLE_COLUMNS: [&str; 7] = ["ax_g", "ay_g", "az_g", "gx_dps", "gy_dps", "gz_dps", "temp_c"];

/// The columns `accelcal stream`'s CSV has before [`SAMPLE_COLUMNS`]: the sample number and its time
/// on the board in seconds.
pub const STREAM_COLUMNS: [&str; 2] = ["index", "time_s"];

/// The last column of `accelcal stream`'s CSV, after [`STREAM_COLUMNS`] and [`SAMPLE_COLUMNS`]:
/// the board's serial.
pub const BOARD_COLUMN: &str = "board";

/// The columns of `accelcal stream`'s CSV, in order.
pub fn stream_csv_columns() -> Vec<&'static str> {
    [STREAM_COLUMNS.as_slice(), &SAMPLE_COLUMNS, &[BOARD_COLUMN]].concat()
}

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
    #[error("{path} holds {extra_bytes} bytes after the {stated} samples its header states (something was appended to it, or `accelcal record` was killed before it updated the header); nothing was read. To read the {stated} samples it states, cut it to them: `truncate -s {keep_bytes} {path}`")]
    PastStated { path: String, stated: u64, extra_bytes: u64, keep_bytes: u64 },
    #[error("{path} is cut short: it holds {held} complete samples where its header promises {stated}; nothing was read. Copy it again from the original (a copy or download that did not finish cuts a file short)")]
    CutShort { path: String, held: u64, stated: u64 },
}
