//! Writing a recording as it streams: samples are gathered into blocks; each block is appended and
//! then the header's count is rewritten, so the file on disk always loads.

use std::fs::File;
use std::io::{Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

use shared::protocol::Sample;

use super::{header, RecordingError, BLOCK_SAMPLES, RECORD_BYTES};

/// A recording being written.
pub struct Recorder {
    file: File,
    path: PathBuf,
    block: Vec<u8>,
    /// Samples on disk (complete blocks written).
    written: u64,
    /// Samples per second, named in the header.
    rate_hz: u16,
    /// The serial of the board recorded, named in the header.
    serial: String,
}

impl Recorder {
    /// Creates (or replaces) the file at `path` with an empty recording at `rate_hz` of the board
    /// with the serial `serial`.
    pub fn create(path: &Path, rate_hz: u16, serial: &str) -> Result<Self, RecordingError> {
        let file = File::create(path).map_err(|source| io(path, source))?;
        let mut recorder = Recorder {
            file,
            path: path.to_owned(),
            block: Vec::with_capacity(BLOCK_SAMPLES * RECORD_BYTES),
            written: 0,
            rate_hz,
            serial: serial.to_owned(),
        };
        recorder.write_header()?;
        Ok(recorder)
    }

    /// Adds one sample; a full block goes to disk.
    pub fn push(&mut self, sample: &Sample) -> Result<(), RecordingError> {
        encode(sample, &mut self.block);
        if self.block.len() >= BLOCK_SAMPLES * RECORD_BYTES {
            self.flush_block()?;
        }
        Ok(())
    }

    /// Writes the last, partial block; returns the samples in the file.
    pub fn finish(mut self) -> Result<u64, RecordingError> {
        self.flush_block()?;
        self.file.sync_all().map_err(|source| io(&self.path, source))?;
        Ok(self.written)
    }

    fn flush_block(&mut self) -> Result<(), RecordingError> {
        self.file.write_all(&self.block).map_err(|source| io(&self.path, source))?;
        self.written += (self.block.len() / RECORD_BYTES) as u64;
        self.block.clear();
        self.write_header()
    }

    /// NOTE: the samples go first and the count after, so a crash between the two leaves a stale
    /// (smaller) count that numpy still loads; our reader counts the complete records instead.
    fn write_header(&mut self) -> Result<(), RecordingError> {
        let at_end = (|| {
            self.file.seek(SeekFrom::Start(0))?;
            self.file.write_all(&header::render(self.written, self.rate_hz, &self.serial))?;
            self.file.seek(SeekFrom::End(0))
        })();
        at_end.map(|_| ()).map_err(|source| io(&self.path, source))
    }
}

/// Appends one sample's record (its time is implied by its index, see [`RECORD_BYTES`]).
pub fn encode(sample: &Sample, out: &mut Vec<u8>) {
    out.extend_from_slice(&sample.index.to_le_bytes());
    for value in sample.accel_g.iter().chain(&sample.gyro_dps).chain([&sample.temp_c]) {
        out.extend_from_slice(&value.to_le_bytes());
    }
}

fn io(path: &Path, source: std::io::Error) -> RecordingError {
    RecordingError::Io { path: path.display().to_string(), source }
}
