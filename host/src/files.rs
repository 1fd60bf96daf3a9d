//! Files written so that a crash leaves either the old file or the new one, and the clock the records
//! in them carry. Below every module that keeps a file (sessions, the self-test history, exports).

use std::io::Write;
use std::path::Path;

/// Now, in seconds since the Unix epoch.
pub fn unix_time_s() -> f64 {
    std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0.0, |d| d.as_secs_f64())
}

/// Writes a file so that a crash leaves either the old file or the new one, never half of one:
/// a temporary file beside it, flushed to disk, then renamed over it.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let extension = path.extension().and_then(|e| e.to_str()).unwrap_or("");
    let temporary = path.with_extension(format!("{extension}.tmp{}", std::process::id()));
    let mut file = std::fs::File::create(&temporary)?;
    file.write_all(bytes).and_then(|()| file.sync_all())?;
    std::fs::rename(&temporary, path)
}
