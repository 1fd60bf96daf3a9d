//! The one rule for a file a command is told to write (`record -o`, `export -o`, `certificate
//! issue`, a new stream session's `--stream-log`): a file already there is refused, named, unless the person says to replace it. A
//! recording or an issued certificate cannot be made again; a session's report page, which its
//! session makes again, is rewritten.

use std::path::{Path, PathBuf};

use super::args::Overwrite;
use crate::error::Error;

impl Overwrite {
    /// `Err` naming `path` when it is a file already there and replacing it was not asked for;
    /// `other` is the way out besides --overwrite. A device or a pipe (`/dev/stdout`) is written
    /// through, never refused.
    pub fn check(self, path: &Path, other: &'static str) -> Result<(), Error> {
        match std::fs::metadata(path) {
            Ok(existing) if existing.is_file() && !self.overwrite => {
                Err(Error::OutputExists { path: PathBuf::from(path), other })
            }
            _ => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_existing_file_is_refused_unless_replacing_it_was_asked_for_and_a_device_is_written_through() {
        let path = std::env::temp_dir().join(format!("accelcal-overwrite-{}.npy", std::process::id()));
        let _ = std::fs::remove_file(&path);
        assert!(Overwrite { overwrite: false }.check(&path, "give another -o").is_ok(), "a new file is refused");
        std::fs::write(&path, "kept").unwrap();
        let error = Overwrite { overwrite: false }.check(&path, "give another -o").unwrap_err().to_string();
        let said = format!("{} already exists: give another -o, or add --overwrite to replace it", path.display());
        assert_eq!(error, said);
        assert!(Overwrite { overwrite: true }.check(&path, "give another -o").is_ok());
        assert!(Overwrite { overwrite: false }.check(Path::new("/dev/null"), "give another -o").is_ok());
        let _ = std::fs::remove_file(&path);
    }
}
