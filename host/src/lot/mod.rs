//! The lot database (issue 28): every board's certificates in one SQLite file (embedded, no server),
//! keyed by the board's serial and the calibration's time. Each certificate goes in as one
//! transaction, so a writer killed part way leaves the file as it was before that board; the file is
//! in WAL mode, so another process reads the lot while a session writes to it.

mod error;
pub mod spec;
pub mod summary;
pub mod text;
mod verify;

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use rusqlite::{params, Connection, OpenFlags, TransactionBehavior};

use crate::certificate::Certificate;
use crate::limits::LOT_BUSY_WAIT;
use error::is_busy;
pub use error::LotError;
pub use spec::{Limits, Spec};
pub use summary::{Distribution, LotSummary};

/// The schema's version, in SQLite's `user_version`.
const SCHEMA_VERSION: i64 = 1;
/// One row per certificate (the whole sealed JSON) and one row per certified parameter, for queries.
const SCHEMA: &str = "
CREATE TABLE IF NOT EXISTS certificates (
    id INTEGER PRIMARY KEY,
    serial TEXT NOT NULL,
    date_utc TEXT NOT NULL,
    sha256 TEXT NOT NULL UNIQUE,
    json TEXT NOT NULL
);
CREATE INDEX IF NOT EXISTS certificates_by_board ON certificates (serial, date_utc);
CREATE TABLE IF NOT EXISTS parameters (
    certificate INTEGER NOT NULL REFERENCES certificates (id),
    name TEXT NOT NULL,
    value REAL NOT NULL,
    u REAL NOT NULL,
    expanded REAL NOT NULL,
    unit TEXT NOT NULL,
    PRIMARY KEY (certificate, name)
);";

/// An open lot database.
pub struct Lot {
    connection: Connection,
    path: PathBuf,
    /// A pause inside each write transaction, after the certificate's row and before its
    /// parameters: only for the tests that kill a writer or read beside one mid-transaction.
    pub pause_in_write: Option<Duration>,
}

/// What adding a certificate did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Added {
    New,
    /// The same certificate (by its hash) was already in the lot.
    AlreadyThere,
}

/// Names a pause in seconds inside each write (`Lot::pause_in_write`) of a command that writes a
/// lot: only the tests that kill a writer or read beside one mid-transaction set it.
pub const PAUSE_IN_WRITE_VARIABLE: &str = "ACCELCAL_TEST_LOT_PAUSE_S";

impl Lot {
    /// Opens the lot at `path` for a command to write, pausing in each write when the tests ask
    /// for it ([`PAUSE_IN_WRITE_VARIABLE`]).
    pub fn open_for_writing(path: &Path) -> Result<Self, LotError> {
        let mut lot = Lot::create_or_open(path)?;
        lot.pause_in_write =
            std::env::var(PAUSE_IN_WRITE_VARIABLE).ok().and_then(|s| s.parse().ok()).map(Duration::from_secs_f64);
        Ok(lot)
    }

    /// Adds a certificate just issued to the lot at `path`; what to tell the person.
    pub fn add_issued(path: &Path, certificate: &Certificate) -> Result<String, LotError> {
        Lot::open_for_writing(path)?.add(certificate)?;
        let serial = certificate.board.serial.as_deref().unwrap_or("");
        Ok(format!("certificate of board {serial} added to the lot {}", path.display()))
    }

    /// Opens the lot at `path` for writing, creating the file and its tables when it is new.
    pub fn create_or_open(path: &Path) -> Result<Self, LotError> {
        let connection = Connection::open(path).map_err(|source| LotError::from_sqlite(path, source, open_failed))?;
        let mut lot = Lot { connection, path: path.into(), pause_in_write: None };
        lot.prepare().map_err(|source| LotError::from_sqlite(path, source, open_failed))?;
        lot.check_version()?;
        Ok(lot)
    }

    /// Opens an existing lot for reading only, so that a lot on read-only media or in a folder the
    /// reader cannot write reads too; a missing file is refused, never created.
    pub fn open_existing(path: &Path) -> Result<Self, LotError> {
        if !path.is_file() {
            return Err(LotError::Missing { path: path.into() });
        }
        match Self::open_read_only(path, false) {
            Err(LotError::Open { source, .. }) if cannot_share(&source) => Self::open_read_only(path, true),
            opened => opened,
        }
    }

    /// A read-only connection, `immutable` when the lot cannot be shared.
    ///
    /// NOTE: a WAL reader shares the lot through its `-shm` file, which a reader cannot create in
    /// a folder it cannot write; SQLite then reads the file only as immutable (no writer can add
    /// a WAL beside it there either; the checks of every read refuse a file that changes under it).
    fn open_read_only(path: &Path, immutable: bool) -> Result<Self, LotError> {
        let flags = OpenFlags::SQLITE_OPEN_READ_ONLY | OpenFlags::SQLITE_OPEN_NO_MUTEX | OpenFlags::SQLITE_OPEN_URI;
        let opened = match immutable {
            true => Connection::open_with_flags(immutable_uri(path), flags),
            false => Connection::open_with_flags(path, flags),
        };
        let connection = opened.map_err(|source| LotError::from_sqlite(path, source, open_failed))?;
        let lot = Lot { connection, path: path.into(), pause_in_write: None };
        lot.connection.busy_timeout(LOT_BUSY_WAIT).map_err(|e| lot.read_failed(e))?;
        lot.check_version()?;
        Ok(lot)
    }

    /// The wait for other writers (set before any statement), WAL (readers never wait for a
    /// writer), then the tables and their version as one transaction that waits its turn.
    fn prepare(&mut self) -> rusqlite::Result<()> {
        self.connection.busy_timeout(LOT_BUSY_WAIT)?;
        self.switch_to_wal()?;
        // NOTE: FULL: a committed board survives a power cut too, not only a killed process.
        self.connection.pragma_update(None, "synchronous", "FULL")?;
        let tx = self.connection.transaction_with_behavior(TransactionBehavior::Immediate)?;
        tx.execute_batch(SCHEMA)?;
        tx.pragma_update(None, "user_version", SCHEMA_VERSION)?;
        tx.commit()
    }

    /// Puts the lot in WAL mode, waiting up to [`LOT_BUSY_WAIT`] for other connections.
    ///
    /// NOTE: SQLite answers a change of journal mode that another connection blocks with
    /// SQLITE_BUSY at once, without the busy handler (2 of 60 trials of three writers on a new lot
    /// failed within 0.44 s), so this wait is ours.
    fn switch_to_wal(&self) -> rusqlite::Result<()> {
        let started = Instant::now();
        loop {
            match self.connection.pragma_update_and_check(None, "journal_mode", "WAL", |_| Ok(())) {
                Err(e) if is_busy(&e) && started.elapsed() < LOT_BUSY_WAIT => std::thread::sleep(BUSY_RETRY),
                done => return done,
            }
        }
    }

    /// Refuses a file that is not a lot of this schema (another program's SQLite file, a newer lot).
    fn check_version(&self) -> Result<(), LotError> {
        let version: i64 = self
            .connection
            .pragma_query_value(None, "user_version", |row| row.get(0))
            .map_err(|source| LotError::from_sqlite(&self.path, source, open_failed))?;
        match version {
            SCHEMA_VERSION => Ok(()),
            found => Err(LotError::NotALot { path: self.path.clone(), found }),
        }
    }

    /// Adds a certificate as one transaction: its row and every parameter's, or nothing.
    pub fn add(&mut self, certificate: &Certificate) -> Result<Added, LotError> {
        let serial = certificate.board.serial.as_deref().ok_or(LotError::NoSerial)?;
        let date = certificate.date_utc.as_deref().unwrap_or("");
        let (pause, path) = (self.pause_in_write, self.path.clone());
        let sql = |source| LotError::from_sqlite(&path, source, sql_failed);
        let tx = self.connection.transaction_with_behavior(TransactionBehavior::Immediate).map_err(sql)?;
        let json = certificate.to_json();
        let row = "INSERT OR IGNORE INTO certificates (serial, date_utc, sha256, json) VALUES (?1, ?2, ?3, ?4)";
        if tx.execute(row, params![serial, date, certificate.sha256, json]).map_err(sql)? == 0 {
            return Ok(Added::AlreadyThere);
        }
        let id = tx.last_insert_rowid();
        if let Some(pause) = pause {
            eprintln!("lot: inside the transaction of board {serial}");
            std::thread::sleep(pause);
        }
        let insert =
            "INSERT INTO parameters (certificate, name, value, u, expanded, unit) VALUES (?1, ?2, ?3, ?4, ?5, ?6)";
        for (name, p) in &certificate.parameters {
            tx.execute(insert, params![id, name, p.value, p.u, p.expanded, p.unit]).map_err(sql)?;
        }
        tx.commit().map_err(sql)?;
        Ok(Added::New)
    }

    /// Every board's latest certificate, by serial; each checked (`verify.rs`).
    pub fn latest(&self) -> Result<Vec<Certificate>, LotError> {
        let mut latest: Vec<Certificate> = Vec::new();
        for certificate in self.verified()? {
            match latest.last_mut() {
                Some(last) if last.board.serial == certificate.board.serial => *last = certificate,
                _ => latest.push(certificate),
            }
        }
        Ok(latest)
    }

    /// Every certificate of one board, oldest first; refused when the lot has none. The whole lot is
    /// checked, so a row whose serial was altered cannot hide a certificate from its board.
    pub fn board(&self, serial: &str) -> Result<Vec<Certificate>, LotError> {
        let all = self.verified()?.into_iter();
        let found: Vec<Certificate> = all.filter(|c| c.board.serial.as_deref() == Some(serial)).collect();
        match found.is_empty() {
            true => Err(LotError::UnknownBoard { path: self.path.clone(), serial: serial.into() }),
            false => Ok(found),
        }
    }

    /// The number of certificates and of parameter rows, and whether every certificate has all of its
    /// parameters (SQLite's own integrity check included): what a killed writer must not break.
    pub fn consistency(&self) -> Result<Consistency, LotError> {
        let sql = |source| LotError::from_sqlite(&self.path, source, sql_failed);
        let count = |query: &str| self.connection.query_row(query, [], |row| row.get::<_, i64>(0)).map_err(sql);
        let integrity: String =
            self.connection.query_row("PRAGMA integrity_check", [], |row| row.get(0)).map_err(sql)?;
        let certificates = count("SELECT count(*) FROM certificates")?;
        let parameters = count("SELECT count(*) FROM parameters")?;
        let stated = self.stated_parameter_count()?;
        Ok(Consistency { certificates, parameters, complete: integrity == "ok" && stated == parameters })
    }

    /// The parameters the stored certificates state between them.
    fn stated_parameter_count(&self) -> Result<i64, LotError> {
        Ok(self.verified()?.iter().map(|c| c.parameters.len() as i64).sum())
    }
}

/// How long [`Lot::switch_to_wal`] waits between attempts.
const BUSY_RETRY: Duration = Duration::from_millis(10);

/// Whether a read-only connection failed for want of the WAL's shared-memory file.
fn cannot_share(error: &rusqlite::Error) -> bool {
    use rusqlite::ErrorCode::{CannotOpen, ReadOnly};
    matches!(error.sqlite_error_code(), Some(CannotOpen | ReadOnly))
}

/// The SQLite URI that opens `path` as immutable (`%`, `?` and `#` escaped, as URIs need).
fn immutable_uri(path: &Path) -> String {
    let escaped = path.to_string_lossy().replace('%', "%25").replace('?', "%3f").replace('#', "%23");
    format!("file:{escaped}?immutable=1")
}

fn open_failed(path: PathBuf, source: rusqlite::Error) -> LotError {
    LotError::Open { path, source }
}

fn sql_failed(path: PathBuf, source: rusqlite::Error) -> LotError {
    LotError::Sql { path, source }
}

/// What [`Lot::consistency`] found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Consistency {
    pub certificates: i64,
    pub parameters: i64,
    /// SQLite's integrity check passed and the parameter rows are exactly those the certificates state.
    pub complete: bool,
}

#[cfg(test)]
mod tests;
