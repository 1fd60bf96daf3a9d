//! The lot on a PostgreSQL server (issue 41): many stations write to one lot over the network, where
//! a SQLite file on a share is not to be trusted. The same tables and statements as the file
//! (`schema.rs`); the schema's version is kept in the table `accelcal_schema`, and the migrations run
//! under an advisory lock, so stations that start together migrate a new lot once.

use std::path::{Path, PathBuf};
use std::time::Duration;

use postgres::{Client, NoTls};

use super::added::{pause_inside, Added};
use super::schema::{self, NewRow, ParameterRow, Stored, LATEST, MIGRATIONS};
use super::LotError;

/// The advisory lock the migrations hold (any number all accelcal stations agree on: "AC41").
const MIGRATION_LOCK: i64 = 0x4143_3431;
/// How long a station waits for the server to answer before its certificate stays queued.
const CONNECT_TIMEOUT: Duration = Duration::from_secs(5);

/// Whether `place` names a lot on a server rather than a file.
pub fn is_server(place: &Path) -> bool {
    let text = place.to_string_lossy();
    text.starts_with("postgres://") || text.starts_with("postgresql://")
}

/// The server's address as messages name it: its password left out.
pub fn shown(url: &str) -> PathBuf {
    let Some((scheme, rest)) = url.split_once("://") else { return url.into() };
    match rest.split_once('@') {
        Some((user, host)) if user.contains(':') => {
            format!("{scheme}://{}:***@{host}", user.split(':').next().unwrap_or_default()).into()
        }
        _ => url.into(),
    }
}

/// Connects to the lot's server.
pub(super) fn connect(url: &str, place: &Path) -> Result<Client, LotError> {
    let mut config: postgres::Config =
        url.parse().map_err(|e: postgres::Error| LotError::Address { place: place.into(), reason: e.to_string() })?;
    config.connect_timeout(CONNECT_TIMEOUT);
    config.connect(NoTls).map_err(|source| failed(place, source))
}

/// Brings the server's tables to [`LATEST`], once however many stations start together.
pub(super) fn migrate(client: &mut Client, place: &Path) -> Result<(), LotError> {
    let sql = |source| failed(place, source);
    let mut tx = client.transaction().map_err(sql)?;
    tx.execute("SELECT pg_advisory_xact_lock($1)", &[&MIGRATION_LOCK]).map_err(sql)?;
    tx.batch_execute("CREATE TABLE IF NOT EXISTS accelcal_schema (version BIGINT NOT NULL)").map_err(sql)?;
    let found: i64 = tx.query_one("SELECT coalesce(max(version), 0) FROM accelcal_schema", &[]).map_err(sql)?.get(0);
    if found > LATEST {
        return Err(LotError::NotALot { path: place.into(), found });
    }
    for migration in MIGRATIONS.iter().filter(|m| m.version > found) {
        tx.batch_execute(migration.server).map_err(sql)?;
        tx.execute("INSERT INTO accelcal_schema (version) VALUES ($1)", &[&migration.version]).map_err(sql)?;
    }
    tx.commit().map_err(sql)
}

/// The server lot's schema version, for reading: refused when it holds no lot or another version.
pub(super) fn check_version(client: &mut Client, place: &Path) -> Result<(), LotError> {
    let sql = |source| failed(place, source);
    let exists: bool = client.query_one("SELECT to_regclass('accelcal_schema') IS NOT NULL", &[]).map_err(sql)?.get(0);
    if !exists {
        return Err(LotError::NoLotOnServer { place: place.into() });
    }
    let found: i64 =
        client.query_one("SELECT coalesce(max(version), 0) FROM accelcal_schema", &[]).map_err(sql)?.get(0);
    match found {
        LATEST => Ok(()),
        found => Err(LotError::NotALot { path: place.into(), found }),
    }
}

/// Adds a certificate as one transaction: its row and every parameter's, or nothing (a station
/// killed part way drops its connection, and the server rolls the transaction back).
pub(super) fn insert(
    client: &mut Client,
    place: &Path,
    row: &NewRow,
    pause: Option<Duration>,
) -> Result<Added, LotError> {
    let sql = |source| failed(place, source);
    let mut tx = client.transaction().map_err(sql)?;
    let values: [&(dyn postgres::types::ToSql + Sync); 5] =
        [&row.serial, &row.date_utc, &row.sha256, &row.json, &row.station];
    let Some(id) = tx.query_opt(schema::INSERT_CERTIFICATE, &values).map_err(sql)? else {
        return Ok(Added::AlreadyThere);
    };
    let id: i64 = id.get(0);
    pause_inside(row.serial, pause);
    let statement = tx.prepare(schema::INSERT_PARAMETER).map_err(sql)?;
    for (name, (value, u, expanded, unit)) in &row.parameters {
        tx.execute(&statement, &[&id, name, value, u, expanded, unit]).map_err(sql)?;
    }
    tx.commit().map_err(sql)?;
    Ok(Added::New)
}

/// The `certificates` rows.
pub(super) fn stored(client: &mut Client, place: &Path) -> Result<Vec<Stored>, LotError> {
    let rows = client.query(schema::SELECT_CERTIFICATES, &[]).map_err(|e| failed(place, e))?;
    let stored = |r: &postgres::Row| Stored {
        id: r.get(0),
        serial: r.get(1),
        date_utc: r.get(2),
        sha256: r.get(3),
        json: r.get(4),
        station: r.get(5),
    };
    Ok(rows.iter().map(stored).collect())
}

/// Every `parameters` row as (certificate id, name, values).
pub(super) fn parameter_rows(client: &mut Client, place: &Path) -> Result<Vec<(i64, String, ParameterRow)>, LotError> {
    let rows = client.query(schema::SELECT_PARAMETERS, &[]).map_err(|e| failed(place, e))?;
    Ok(rows.iter().map(|r| (r.get(0), r.get(1), (r.get(2), r.get(3), r.get(4), r.get(5)))).collect())
}

/// One count (`schema::COUNT_*`).
pub(super) fn count(client: &mut Client, place: &Path, query: &str) -> Result<i64, LotError> {
    Ok(client.query_one(query, &[]).map_err(|e| failed(place, e))?.get(0))
}

/// A server's failure, with the server's own words where it gave some (postgres' Display of a
/// database error is only "db error").
fn failed(place: &Path, source: postgres::Error) -> LotError {
    let reason = match source.as_db_error() {
        Some(said) => format!("{}: {}", said.severity(), said.message()),
        None => match std::error::Error::source(&source) {
            Some(inner) => format!("{source}: {inner}"),
            None => source.to_string(),
        },
    };
    LotError::Server { place: place.into(), reason }
}
