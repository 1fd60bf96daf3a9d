//! Files written so that a crash leaves either the old file or the new one, and the clock the records
//! in them carry. Below every module that keeps a file (sessions, the self-test history, exports).

use std::io::Write;
use std::path::{Path, PathBuf};

pub mod lock;

/// Now, in seconds since the Unix epoch.
pub fn unix_time_s() -> f64 {
    std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0.0, |d| d.as_secs_f64())
}

/// Writes a file so that a crash leaves either the old file or the new one, never half of one:
/// a temporary file beside it, flushed to disk, then renamed over it; a write that fails leaves
/// the old file and removes its temporary.
///
/// A path that names something other than a file (`/dev/null`, `/dev/stdout`, a named pipe) is
/// written in place: renaming over it would replace the device with a file, and as root that
/// breaks `/dev/null` for every program on the machine. A symbolic link keeps pointing where it
/// did; the file it names is the one replaced.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let path = match std::fs::metadata(path) {
        Ok(existing) if !existing.is_file() => {
            return std::fs::OpenOptions::new().write(true).open(path)?.write_all(bytes)
        }
        Ok(_) => std::fs::canonicalize(path)?,
        Err(_) => path.to_owned(),
    };
    let temporary = temporary_beside(&path);
    let written = std::fs::File::create(&temporary)
        .and_then(|mut file| file.write_all(bytes).and_then(|()| file.sync_all()))
        .and_then(|()| std::fs::rename(&temporary, &path));
    // NOTE: a write cut short (a full disk, a file size limit) leaves the old file as it was and
    // no half-written temporary beside it.
    if written.is_err() {
        let _ = std::fs::remove_file(&temporary);
    }
    written
}

fn temporary_beside(path: &Path) -> PathBuf {
    let extension = path.extension().and_then(|e| e.to_str()).unwrap_or("");
    path.with_extension(format!("{extension}.tmp{}", std::process::id()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::os::unix::fs::FileTypeExt;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("accelcal-files-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn a_named_pipe_is_written_through_and_stays_a_pipe() {
        let dir = scratch("pipe");
        let pipe = dir.join("out.json");
        let made = std::process::Command::new("mkfifo").arg(&pipe).status().expect("mkfifo (coreutils) runs");
        assert!(made.success());
        let reader = {
            let pipe = pipe.clone();
            std::thread::spawn(move || std::fs::read(pipe).unwrap())
        };
        write_atomically(&pipe, b"{\"m\": 1}").unwrap();
        assert!(std::fs::symlink_metadata(&pipe).unwrap().file_type().is_fifo(), "the pipe was replaced by a file");
        assert_eq!(reader.join().unwrap(), b"{\"m\": 1}");
    }

    #[test]
    fn a_symbolic_link_keeps_pointing_at_its_file_which_gets_the_bytes() {
        let dir = scratch("link");
        let (file, link) = (dir.join("real.json"), dir.join("link.json"));
        std::fs::write(&file, "old").unwrap();
        std::os::unix::fs::symlink(&file, &link).unwrap();
        write_atomically(&link, b"new").unwrap();
        assert!(std::fs::symlink_metadata(&link).unwrap().file_type().is_symlink());
        assert_eq!(std::fs::read(&file).unwrap(), b"new");
    }

    #[test]
    fn a_new_file_is_written_and_no_temporary_is_left() {
        let dir = scratch("new");
        let path = dir.join("cal.h");
        write_atomically(&path, b"x").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"x");
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
    }
}
