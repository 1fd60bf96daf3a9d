//! The lot in one SQLite file (issue 28): embedded, no server. The file is in WAL mode, so another
//! process reads the lot while a session writes to it; each certificate goes in as one transaction.

use std::path::Path;
use std::time::{Duration, Instant};

use rusqlite::{params, Connection, OpenFlags, TransactionBehavior};

use super::added::{pause_inside, Added};
use super::error::is_busy;
use super::schema::{self, NewRow, ParameterRow, Stored, LATEST, MIGRATIONS};
use super::LotError;
use crate::limits::LOT_BUSY_WAIT;

/// How long [`switch_to_wal`] waits between attempts.
const BUSY_RETRY: Duration = Duration::from_millis(10);

/// Opens the lot at `path` for writing, creating the file and its tables when it is new and
/// migrating an older one.
pub(super) fn create_or_open(path: &Path) -> Result<Connection, LotError> {
    let opened = |source| LotError::from_sqlite(path, source, open_failed);
    let mut connection = Connection::open(path).map_err(opened)?;
    connection.busy_timeout(LOT_BUSY_WAIT).map_err(opened)?;
    switch_to_wal(&connection).map_err(opened)?;
    // NOTE: FULL: a committed board survives a power cut too, not only a killed process.
    connection.pragma_update(None, "synchronous", "FULL").map_err(opened)?;
    let tx = connection.transaction_with_behavior(TransactionBehavior::Immediate).map_err(opened)?;
    let found: i64 = tx.pragma_query_value(None, "user_version", |row| row.get(0)).map_err(opened)?;
    if !(0..=LATEST).contains(&found) {
        return Err(LotError::NotALot { path: path.into(), found });
    }
    for migration in MIGRATIONS.iter().filter(|m| m.version > found) {
        tx.execute_batch(migration.file).map_err(opened)?;
    }
    tx.pragma_update(None, "user_version", LATEST).map_err(opened)?;
    tx.commit().map_err(opened)?;
    Ok(connection)
}

/// Puts the lot in WAL mode, waiting up to [`LOT_BUSY_WAIT`] for other connections.
///
/// NOTE: SQLite answers a change of journal mode that another connection blocks with
/// SQLITE_BUSY at once, without the busy handler (2 of 60 trials of three writers on a new lot
/// failed within 0.44 s), so this wait is ours.
fn switch_to_wal(connection: &Connection) -> rusqlite::Result<()> {
    let started = Instant::now();
    loop {
        match connection.pragma_update_and_check(None, "journal_mode", "WAL", |_| Ok(())) {
            Err(e) if is_busy(&e) && started.elapsed() < LOT_BUSY_WAIT => std::thread::sleep(BUSY_RETRY),
            done => return done,
        }
    }
}

/// A read-only connection and its schema's version, `immutable` when the lot cannot be shared.
///
/// NOTE: a WAL reader shares the lot through its `-shm` file, which a reader cannot create in
/// a folder it cannot write; SQLite then reads the file only as immutable (no writer can add
/// a WAL beside it there either; the checks of every read refuse a file that changes under it).
pub(super) fn open_read_only(path: &Path, immutable: bool) -> Result<(Connection, i64), LotError> {
    let flags = OpenFlags::SQLITE_OPEN_READ_ONLY | OpenFlags::SQLITE_OPEN_NO_MUTEX | OpenFlags::SQLITE_OPEN_URI;
    let opened = match immutable {
        true => Connection::open_with_flags(immutable_uri(path), flags),
        false => Connection::open_with_flags(path, flags),
    };
    let connection = opened.map_err(|source| LotError::from_sqlite(path, source, open_failed))?;
    connection.busy_timeout(LOT_BUSY_WAIT).map_err(|e| read_failed(path, e))?;
    let version: i64 = connection
        .pragma_query_value(None, "user_version", |row| row.get(0))
        .map_err(|source| LotError::from_sqlite(path, source, open_failed))?;
    match version {
        1..=LATEST => Ok((connection, version)),
        found => Err(LotError::NotALot { path: path.into(), found }),
    }
}

/// The SQLite URI that opens `path` as immutable (`%`, `?` and `#` escaped, as URIs need).
fn immutable_uri(path: &Path) -> String {
    let escaped = path.to_string_lossy().replace('%', "%25").replace('?', "%3f").replace('#', "%23");
    format!("file:{escaped}?immutable=1")
}

/// Adds a certificate as one transaction: its row and every parameter's, or nothing.
pub(super) fn insert(
    connection: &mut Connection,
    path: &Path,
    row: &NewRow,
    pause: Option<Duration>,
) -> Result<Added, LotError> {
    let sql = |source| LotError::from_sqlite(path, source, sql_failed);
    let tx = connection.transaction_with_behavior(TransactionBehavior::Immediate).map_err(sql)?;
    let values = params![row.serial, row.date_utc, row.sha256, row.json, row.station];
    let mut inserted = tx.prepare(schema::INSERT_CERTIFICATE).map_err(sql)?;
    let id: Option<i64> = inserted.query_map(values, |r| r.get(0)).map_err(sql)?.next().transpose().map_err(sql)?;
    drop(inserted);
    let Some(id) = id else { return Ok(Added::AlreadyThere) };
    pause_inside(row.serial, pause);
    for (name, (value, u, expanded, unit)) in &row.parameters {
        tx.execute(schema::INSERT_PARAMETER, params![id, name, value, u, expanded, unit]).map_err(sql)?;
    }
    tx.commit().map_err(sql)?;
    Ok(Added::New)
}

/// The `certificates` rows of a schema of `version`.
pub(super) fn stored(connection: &Connection, path: &Path, version: i64) -> Result<Vec<Stored>, LotError> {
    let query = if version < 2 { schema::SELECT_CERTIFICATES_V1 } else { schema::SELECT_CERTIFICATES };
    let mut statement = connection.prepare(query).map_err(|e| read_failed(path, e))?;
    let row = |row: &rusqlite::Row| {
        let (id, serial, date_utc, sha256, json) = (row.get(0)?, row.get(1)?, row.get(2)?, row.get(3)?, row.get(4)?);
        Ok(Stored { id, serial, date_utc, sha256, json, station: row.get(5)? })
    };
    let rows = statement.query_map([], row).map_err(|e| read_failed(path, e))?;
    rows.collect::<Result<_, _>>().map_err(|e| read_failed(path, e))
}

/// Every `parameters` row as (certificate id, name, values).
pub(super) fn parameter_rows(
    connection: &Connection,
    path: &Path,
) -> Result<Vec<(i64, String, ParameterRow)>, LotError> {
    let mut statement = connection.prepare(schema::SELECT_PARAMETERS).map_err(|e| read_failed(path, e))?;
    let row =
        |row: &rusqlite::Row| Ok((row.get(0)?, row.get(1)?, (row.get(2)?, row.get(3)?, row.get(4)?, row.get(5)?)));
    let rows = statement.query_map([], row).map_err(|e| read_failed(path, e))?;
    rows.collect::<Result<_, _>>().map_err(|e| read_failed(path, e))
}

/// SQLite's integrity check: pages, records and indexes as SQLite wrote them; what it found.
pub(super) fn integrity(connection: &Connection, path: &Path) -> Result<Vec<String>, LotError> {
    let mut statement = connection.prepare("PRAGMA integrity_check").map_err(|e| read_failed(path, e))?;
    let rows = statement.query_map([], |row| row.get::<_, String>(0)).map_err(|e| read_failed(path, e))?;
    rows.collect::<Result<_, _>>().map_err(|e| read_failed(path, e))
}

/// One count (`schema::COUNT_*`).
pub(super) fn count(connection: &Connection, path: &Path, query: &str) -> Result<i64, LotError> {
    connection.query_row(query, [], |row| row.get(0)).map_err(|e| LotError::from_sqlite(path, e, sql_failed))
}

/// A failed read: a lot another process holds is named as such, anything else as a damaged file.
fn read_failed(path: &Path, source: rusqlite::Error) -> LotError {
    LotError::from_sqlite(path, source, |path, source| LotError::Damaged { path, reason: source.to_string() })
}

fn open_failed(path: std::path::PathBuf, source: rusqlite::Error) -> LotError {
    LotError::Open { path, source }
}

fn sql_failed(path: std::path::PathBuf, source: rusqlite::Error) -> LotError {
    LotError::Sql { path, source }
}
