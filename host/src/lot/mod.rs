//! The lot database: every board's certificates, keyed by the board's serial and the calibration's
//! time, in one SQLite file (issue 28: embedded, no server; `file.rs`) or on a PostgreSQL server that
//! many stations write to (issue 41: `server.rs`), with one schema and its numbered migrations
//! (`schema.rs`). Each certificate goes in as one transaction, so a writer killed part way leaves the
//! lot as it was before that board; every read re-checks what it shows (`verify.rs`). A station
//! keeps each certificate in its own queue before it uploads it to a server (`queue.rs`).

mod added;
mod error;
mod file;
mod issued;
pub mod queue;
mod schema;
pub mod server;
pub mod spec;
pub mod stations;
pub mod summary;
pub mod text;
mod verify;

use std::cell::RefCell;
use std::path::{Path, PathBuf};
use std::time::Duration;

use crate::certificate::Certificate;
pub use added::Added;
pub use error::LotError;
use schema::NewRow;
pub use spec::{Limits, Spec};
pub use summary::{Distribution, LotSummary};

/// An open lot database.
pub struct Lot {
    backend: Backend,
    /// What messages name: the file, or the server's address without its password.
    path: PathBuf,
    /// The schema's version the lot holds (older only in a file read without writing).
    version: i64,
    /// A pause inside each write transaction, after the certificate's row and before its
    /// parameters: only for the tests that kill a writer or read beside one mid-transaction.
    pub pause_in_write: Option<Duration>,
    /// The station each certificate added is recorded from.
    pub station: String,
}

/// Where the lot's tables are.
enum Backend {
    File(rusqlite::Connection),
    /// NOTE: in a cell: the client's every call takes it mutably, the lot's reads do not.
    Server(RefCell<postgres::Client>),
}

/// Names a pause in seconds inside each write (`Lot::pause_in_write`) of a command that writes a
/// lot: only the tests that kill a writer or read beside one mid-transaction set it.
pub const PAUSE_IN_WRITE_VARIABLE: &str = "ACCELCAL_TEST_LOT_PAUSE_S";
/// Names the station a command records its certificates from (default: the machine's host name).
pub const STATION_VARIABLE: &str = "ACCELCAL_STATION";

impl Lot {
    /// Opens the lot at `place` (a file, or `postgres://...`) for a command to write, pausing in each
    /// write when the tests ask for it ([`PAUSE_IN_WRITE_VARIABLE`]).
    pub fn open_for_writing(place: &Path) -> Result<Self, LotError> {
        let mut lot = Lot::create_or_open(place)?;
        lot.pause_in_write =
            std::env::var(PAUSE_IN_WRITE_VARIABLE).ok().and_then(|s| s.parse().ok()).map(Duration::from_secs_f64);
        Ok(lot)
    }

    /// Opens the lot at `place` for writing, creating its tables when it is new and migrating an
    /// older schema.
    pub fn create_or_open(place: &Path) -> Result<Self, LotError> {
        if server::is_server(place) {
            let (mut client, shown) = Self::connect(place)?;
            server::migrate(&mut client, &shown)?;
            return Ok(Lot::new(Backend::Server(RefCell::new(client)), shown, schema::LATEST));
        }
        Ok(Lot::new(Backend::File(file::create_or_open(place)?), place.into(), schema::LATEST))
    }

    /// Opens an existing lot for reading only, so that a lot on read-only media or in a folder the
    /// reader cannot write reads too; a missing file (or a server without a lot) is refused, never created.
    pub fn open_existing(place: &Path) -> Result<Self, LotError> {
        if server::is_server(place) {
            let (mut client, shown) = Self::connect(place)?;
            server::check_version(&mut client, &shown)?;
            return Ok(Lot::new(Backend::Server(RefCell::new(client)), shown, schema::LATEST));
        }
        if !place.is_file() {
            return Err(LotError::Missing { path: place.into() });
        }
        let (connection, version) = match file::open_read_only(place, false) {
            Err(LotError::Open { source, .. }) if cannot_share(&source) => file::open_read_only(place, true)?,
            opened => opened?,
        };
        Ok(Lot::new(Backend::File(connection), place.into(), version))
    }

    fn connect(place: &Path) -> Result<(postgres::Client, PathBuf), LotError> {
        let url = place.to_string_lossy();
        let shown = server::shown(&url);
        Ok((server::connect(&url, &shown)?, shown))
    }

    fn new(backend: Backend, path: PathBuf, version: i64) -> Self {
        Lot { backend, path, version, pause_in_write: None, station: this_station() }
    }

    /// Adds a certificate as one transaction: its row and every parameter's, or nothing.
    pub fn add(&mut self, certificate: &Certificate) -> Result<Added, LotError> {
        let serial = certificate.board.serial.as_deref().ok_or(LotError::NoSerial)?;
        let row = NewRow {
            serial,
            date_utc: certificate.date_utc.as_deref().unwrap_or(""),
            sha256: &certificate.sha256,
            json: certificate.to_json(),
            station: &self.station,
            parameters: certificate
                .parameters
                .iter()
                .map(|(name, p)| (name.as_str(), (p.value, p.u, p.expanded, p.unit.clone())))
                .collect(),
        };
        match &mut self.backend {
            Backend::File(connection) => file::insert(connection, &self.path, &row, self.pause_in_write),
            Backend::Server(client) => server::insert(client.get_mut(), &self.path, &row, self.pause_in_write),
        }
    }

    /// Every board's latest certificate, by serial; each checked (`verify.rs`).
    pub fn latest(&self) -> Result<Vec<Certificate>, LotError> {
        let mut latest: Vec<Certificate> = Vec::new();
        for (certificate, _) in self.verified()? {
            match latest.last_mut() {
                Some(last) if last.board.serial == certificate.board.serial => *last = certificate,
                _ => latest.push(certificate),
            }
        }
        Ok(latest)
    }

    /// Every certificate of the lot with the station that added it, each checked, by serial and date.
    pub fn all(&self) -> Result<Vec<(Certificate, String)>, LotError> {
        self.verified()
    }

    /// Every certificate of one board, oldest first; refused when the lot has none. The whole lot is
    /// checked, so a row whose serial was altered cannot hide a certificate from its board.
    pub fn board(&self, serial: &str) -> Result<Vec<Certificate>, LotError> {
        let all = self.verified()?.into_iter().map(|(c, _)| c);
        let found: Vec<Certificate> = all.filter(|c| c.board.serial.as_deref() == Some(serial)).collect();
        match found.is_empty() {
            true => Err(LotError::UnknownBoard { path: self.path.clone(), serial: serial.into() }),
            false => Ok(found),
        }
    }

    /// The number of certificates and of parameter rows, and whether every certificate has all of its
    /// parameters (SQLite's own integrity check included): what a killed writer must not break.
    pub fn consistency(&self) -> Result<Consistency, LotError> {
        let certificates = self.count(schema::COUNT_CERTIFICATES)?;
        let parameters = self.count(schema::COUNT_PARAMETERS)?;
        let intact = self.integrity()? == ["ok"];
        let stated: i64 = self.verified()?.iter().map(|(c, _)| c.parameters.len() as i64).sum();
        Ok(Consistency { certificates, parameters, complete: intact && stated == parameters })
    }

    /// The SQLite connection of a file's lot (the tests' own statements).
    #[cfg(test)]
    fn file_connection(&self) -> &rusqlite::Connection {
        match &self.backend {
            Backend::File(connection) => connection,
            Backend::Server(_) => panic!("a server's lot has no file"),
        }
    }

    fn count(&self, query: &str) -> Result<i64, LotError> {
        match &self.backend {
            Backend::File(connection) => file::count(connection, &self.path, query),
            Backend::Server(client) => server::count(&mut client.borrow_mut(), &self.path, query),
        }
    }
}

/// The station this process records its certificates from: [`STATION_VARIABLE`], else the host name.
pub fn this_station() -> String {
    let named = std::env::var(STATION_VARIABLE).ok().filter(|s| !s.is_empty());
    named.unwrap_or_else(|| std::fs::read_to_string("/proc/sys/kernel/hostname").unwrap_or_default().trim().to_owned())
}

/// Whether a read-only connection failed for want of the WAL's shared-memory file.
fn cannot_share(error: &rusqlite::Error) -> bool {
    use rusqlite::ErrorCode::{CannotOpen, ReadOnly};
    matches!(error.sqlite_error_code(), Some(CannotOpen | ReadOnly))
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
