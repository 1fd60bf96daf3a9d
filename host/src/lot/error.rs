//! Why the lot database cannot do what was asked, each with the way out.

use std::path::PathBuf;

/// A lot database's failure.
#[derive(Debug, thiserror::Error)]
pub enum LotError {
    #[error("cannot open the lot database {}: {source}; give a writable path (a new file is created) or a lot file `accelcal lot add` wrote", .path.display())]
    Open { path: PathBuf, source: rusqlite::Error },
    #[error("{} is no lot database: there is no such file; add certificates to it first with `accelcal lot add {} CERT.json` or `accelcal calibrate --lot {}`", .path.display(), .path.display(), .path.display())]
    Missing { path: PathBuf },
    #[error("{} is not an accelcal lot of this version (schema {found}, this accelcal reads 1 and 2); give the lot file `accelcal lot add` wrote, or a new path; a lot file that was altered or damaged reads so too: add its boards again from their certificate files to a new lot", .path.display())]
    NotALot { path: PathBuf, found: i64 },
    #[error("the lot database {} failed: {source}; nothing of the board being written was kept, run the command again (a lot another process is writing is waited for up to 30 s)", .path.display())]
    Sql { path: PathBuf, source: rusqlite::Error },
    #[error("the lot database {} is held by another writer for more than 30 s; run again once the other session has written its board", .path.display())]
    Busy { path: PathBuf },
    #[error("a certificate in {} does not read back ({reason}); it was stored by another accelcal version: read it with that version", .path.display())]
    Unreadable { path: PathBuf, reason: String },
    #[error("the lot {} was altered or damaged: board {serial}'s {what}; nothing of the lot is shown. The file cannot be trusted: add the boards again from their certificate files to a new lot (`accelcal lot add NEW.sqlite CERT.json...`)", .path.display())]
    Altered { path: PathBuf, serial: String, what: String },
    #[error("the lot database {} is damaged ({reason}); nothing of the lot is shown. The file was altered or damaged: add the boards again from their certificate files to a new lot (`accelcal lot add NEW.sqlite CERT.json...`)", .path.display())]
    Damaged { path: PathBuf, reason: String },
    #[error("the certificate names no board serial, so the lot cannot key it: issue it from a session that recorded its board (calibrate or capture on the board)")]
    NoSerial,
    #[error("{} names no board serial, so the lot cannot key it, and no certificate was added: leave it out, or issue it from a session that recorded its board (calibrate or capture on the board; a board's own stream with --serial)", .file.display())]
    NoSerialIn { file: PathBuf },
    #[error("the lot {} holds no board with serial {serial}; `accelcal lot show {}` lists its boards", .path.display(), .path.display())]
    UnknownBoard { path: PathBuf, serial: String },
    #[error("the lot server {} failed: {reason}; nothing of the board being written was kept there. Certificates waiting in this station's queue are sent by `accelcal lot sync {}` once the server answers", .place.display(), .place.display())]
    Server { place: PathBuf, reason: String },
    #[error("{} is no lot server address ({reason}); write it as postgres://USER[:PASSWORD]@HOST[:PORT]/DATABASE", .place.display())]
    Address { place: PathBuf, reason: String },
    #[error("the server {} holds no accelcal lot yet; add certificates to it first (`accelcal lot add {} CERT.json`, `accelcal lot sync {}`)", .place.display(), .place.display(), .place.display())]
    NoLotOnServer { place: PathBuf },
    #[error("cannot keep the certificate in the station's queue {}: {source}; give a folder this user can write with --queue (or ACCELCAL_LOT_QUEUE)", .dir.display())]
    Queue { dir: PathBuf, source: std::io::Error },
    #[error("{count} certificate file(s) in the station's queue were refused by their hash (altered or damaged) and set aside in {}; issue them again from their sessions (`accelcal certificate issue SESSION.json`)", .dir.display())]
    RefusedInQueue { count: usize, dir: PathBuf },
    #[error("cannot write the records in {}: {source}; give a folder this user can write with --out", .dir.display())]
    Records { dir: PathBuf, source: std::io::Error },
    #[error("cannot read the spec file {}: {reason}; write it as TOML, one `[limits.NAME]` table per parameter with `low` and/or `high` in the certificate's units (docs/production.md)", .path.display())]
    Spec { path: PathBuf, reason: String },
}

impl LotError {
    /// An SQLite failure at `path`: a lot another process holds is named as such, a file SQLite
    /// finds corrupt as damaged, the rest as `make`.
    pub(super) fn from_sqlite(
        path: &std::path::Path,
        source: rusqlite::Error,
        make: fn(PathBuf, rusqlite::Error) -> Self,
    ) -> Self {
        use rusqlite::ErrorCode::{DatabaseCorrupt, NotADatabase};
        match source.sqlite_error_code() {
            _ if is_busy(&source) => LotError::Busy { path: path.into() },
            Some(DatabaseCorrupt | NotADatabase) => LotError::Damaged { path: path.into(), reason: source.to_string() },
            _ => make(path.into(), source),
        }
    }
}

/// Whether SQLite refused because another connection holds the lot.
pub(super) fn is_busy(error: &rusqlite::Error) -> bool {
    use rusqlite::ErrorCode::{DatabaseBusy, DatabaseLocked};
    matches!(error.sqlite_error_code(), Some(DatabaseBusy | DatabaseLocked))
}
