//! A file that one run at a time writes: an OS advisory lock on a lock file beside it, which names
//! its holder for a run that finds it held. The OS drops the lock when the process ends, however it
//! ends (a `kill -9` too), so a lock left behind never blocks.

use std::fs::{File, OpenOptions, TryLockError};
use std::io::{Read, Seek, Write};
use std::os::unix::fs::MetadataExt;
use std::path::{Path, PathBuf};

/// A lock held by this process; dropped on every way out of the run (the lock file removed, then
/// closed, which releases it).
#[derive(Debug)]
pub struct Held {
    path: PathBuf,
    // NOTE: declared last, so that it closes (and unlocks) after the file was removed in `drop`.
    _file: File,
}

impl Drop for Held {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.path);
    }
}

/// Takes the lock of `path` (the file `PATH.lock`) for this process, which any run that finds it
/// held is told as `holder` (the pid and the board, say); `Ok(Err(holder))` when another holds it.
pub fn hold(path: &Path, holder: &str) -> std::io::Result<Result<Held, String>> {
    let lock_path = lock_file(path);
    loop {
        let mut file = OpenOptions::new().read(true).write(true).create(true).truncate(false).open(&lock_path)?;
        match file.try_lock() {
            Ok(()) => {}
            Err(TryLockError::WouldBlock) => return Ok(Err(holder_of(&mut file))),
            Err(TryLockError::Error(error)) => return Err(error),
        }
        // NOTE: a holder that ended removed its lock file after this run opened it: the lock on the
        // removed file guards nothing, so this run takes the file now at the path instead.
        if is_at(&file, &lock_path) {
            file.set_len(0)?;
            file.write_all(holder.as_bytes())?;
            return Ok(Ok(Held { path: lock_path, _file: file }));
        }
    }
}

/// The lock file of `path`: `PATH.lock` beside it.
pub fn lock_file(path: &Path) -> PathBuf {
    let mut name = path.as_os_str().to_owned();
    name.push(".lock");
    PathBuf::from(name)
}

/// Whom the holder named (written just after it took the lock: empty for that instant).
fn holder_of(file: &mut File) -> String {
    let mut holder = String::new();
    let _ = file.rewind().and_then(|()| file.read_to_string(&mut holder));
    match holder.trim() {
        "" => "another run of accelcal".to_owned(),
        named => named.to_owned(),
    }
}

/// Whether `file` is the file at `path` (not one removed from there).
fn is_at(file: &File, path: &Path) -> bool {
    match (file.metadata(), std::fs::metadata(path)) {
        (Ok(open), Ok(there)) => open.dev() == there.dev() && open.ino() == there.ino(),
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("accelcal-lock-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir.join("z")
    }

    #[test]
    fn a_held_file_is_refused_naming_its_holder_and_free_again_once_dropped() {
        let path = scratch("held");
        let first = hold(&path, "pid 7, board AB12").unwrap().unwrap();
        assert_eq!(hold(&path, "pid 8, board CD34").unwrap().unwrap_err(), "pid 7, board AB12");
        drop(first);
        assert!(!lock_file(&path).exists(), "the lock file is left behind");
        let again = hold(&path, "pid 8, board CD34").unwrap();
        assert!(again.is_ok(), "a dropped lock still blocks");
    }

    #[test]
    fn a_lock_file_left_by_a_killed_run_does_not_block() {
        let path = scratch("left");
        std::fs::write(lock_file(&path), "pid 1, board AB12").unwrap();
        let held = hold(&path, "pid 9, board CD34").unwrap();
        assert!(held.is_ok(), "a lock file no process holds blocks");
        assert_eq!(std::fs::read_to_string(lock_file(&path)).unwrap(), "pid 9, board CD34");
    }
}
