//! Every read of the lot re-checks what it is about to show (issue 40): SQLite's own integrity check,
//! each stored certificate against its hash and against the serial and date it is keyed by, and the
//! `parameters` rows against the certificates they come from. A lot file that was altered or damaged
//! is refused naming the board, never shown with a changed figure.

use std::collections::BTreeMap;

use super::{Lot, LotError};
use crate::certificate::{digest_of, Certificate};

/// One row of `certificates` as stored.
struct Stored {
    id: i64,
    serial: String,
    date_utc: String,
    sha256: String,
    json: String,
}

/// One row of `parameters`: (value, u, U, unit).
type ParameterRow = (f64, f64, f64, String);

impl Lot {
    /// Every certificate of the lot, by serial, then date, then the order added; each checked.
    pub(super) fn verified(&self) -> Result<Vec<Certificate>, LotError> {
        self.check_integrity()?;
        let mut parameters = self.parameter_rows()?;
        let mut certificates = Vec::new();
        for stored in self.stored()? {
            let certificate = self.checked(&stored)?;
            let rows = parameters.remove(&stored.id).unwrap_or_default();
            self.check_parameters(&stored, &certificate, &rows)?;
            certificates.push(certificate);
        }
        match parameters.keys().next() {
            Some(id) => Err(self.damaged(format!("parameter rows of certificate {id}, which the lot does not hold"))),
            None => Ok(certificates),
        }
    }

    /// SQLite's integrity check: pages, records and indexes as SQLite wrote them.
    fn check_integrity(&self) -> Result<(), LotError> {
        let mut statement = self.connection.prepare("PRAGMA integrity_check").map_err(|e| self.read_failed(e))?;
        let rows = statement.query_map([], |row| row.get::<_, String>(0)).map_err(|e| self.read_failed(e))?;
        let found: Vec<String> = rows.collect::<Result<_, _>>().map_err(|e| self.read_failed(e))?;
        match found.as_slice() {
            [ok] if ok == "ok" => Ok(()),
            _ => Err(self.damaged(format!("SQLite's integrity check found: {}", found.join("; ")))),
        }
    }

    /// The `certificates` rows, by serial, date and id.
    fn stored(&self) -> Result<Vec<Stored>, LotError> {
        let query = "SELECT id, serial, date_utc, sha256, json FROM certificates ORDER BY serial, date_utc, id";
        let mut statement = self.connection.prepare(query).map_err(|e| self.read_failed(e))?;
        let row = |row: &rusqlite::Row| {
            let (id, serial, date_utc, sha256, json) =
                (row.get(0)?, row.get(1)?, row.get(2)?, row.get(3)?, row.get(4)?);
            Ok(Stored { id, serial, date_utc, sha256, json })
        };
        let rows = statement.query_map([], row).map_err(|e| self.read_failed(e))?;
        rows.collect::<Result<_, _>>().map_err(|e| self.read_failed(e))
    }

    /// Every `parameters` row, by certificate id and name.
    fn parameter_rows(&self) -> Result<BTreeMap<i64, BTreeMap<String, ParameterRow>>, LotError> {
        let query = "SELECT certificate, name, value, u, expanded, unit FROM parameters";
        let mut statement = self.connection.prepare(query).map_err(|e| self.read_failed(e))?;
        let row =
            |row: &rusqlite::Row| Ok((row.get(0)?, row.get(1)?, (row.get(2)?, row.get(3)?, row.get(4)?, row.get(5)?)));
        let rows = statement.query_map([], row).map_err(|e| self.read_failed(e))?;
        let mut by_certificate: BTreeMap<i64, BTreeMap<String, ParameterRow>> = BTreeMap::new();
        for found in rows {
            let (id, name, values) = found.map_err(|e| self.read_failed(e))?;
            by_certificate.entry(id).or_default().insert(name, values);
        }
        Ok(by_certificate)
    }

    /// The certificate a row holds, when its content hashes to the hash it states and the row
    /// keeps, and it names the serial and date the row is keyed by.
    fn checked(&self, stored: &Stored) -> Result<Certificate, LotError> {
        let altered = |what: String| self.altered(&stored.serial, what);
        let value: serde_json::Value = serde_json::from_str(&stored.json)
            .map_err(|e| altered(format!("certificate is no JSON any more ({e})")))?;
        let found = digest_of(value.clone());
        let stated = value.get("sha256").and_then(|s| s.as_str()).unwrap_or_default();
        if found != stored.sha256 || found != stated {
            return Err(altered(format!(
                "certificate hashes to {found}, but it states {stated} and was stored as {}",
                stored.sha256
            )));
        }
        let certificate: Certificate = serde_json::from_value(value)
            .map_err(|e| LotError::Unreadable { path: self.path.clone(), reason: e.to_string() })?;
        let keyed = (Some(stored.serial.as_str()), stored.date_utc.as_str());
        match (certificate.board.serial.as_deref(), certificate.date_utc.as_deref().unwrap_or("")) == keyed {
            true => Ok(certificate),
            false => Err(altered(format!(
                "row is keyed by serial {} and date {:?}, which its certificate does not state",
                stored.serial, stored.date_utc
            ))),
        }
    }

    /// Refuses `parameters` rows that differ from the certificate's parameters, or are missing or extra.
    fn check_parameters(
        &self,
        stored: &Stored,
        certificate: &Certificate,
        rows: &BTreeMap<String, ParameterRow>,
    ) -> Result<(), LotError> {
        let stated: BTreeMap<String, ParameterRow> = certificate
            .parameters
            .iter()
            .map(|(name, p)| (name.clone(), (p.value, p.u, p.expanded, p.unit.clone())))
            .collect();
        let differing = stated.keys().chain(rows.keys()).find(|name| stated.get(*name) != rows.get(*name));
        match differing {
            Some(name) => Err(self.altered(
                &stored.serial,
                format!("`parameters` row {name} differs from (or is missing beside) what its certificate states"),
            )),
            None => Ok(()),
        }
    }

    fn altered(&self, serial: &str, what: String) -> LotError {
        LotError::Altered { path: self.path.clone(), serial: serial.to_owned(), what }
    }

    fn damaged(&self, reason: String) -> LotError {
        LotError::Damaged { path: self.path.clone(), reason }
    }

    /// A failed read: a lot another process holds is named as such, anything else as a damaged file.
    pub(super) fn read_failed(&self, source: rusqlite::Error) -> LotError {
        LotError::from_sqlite(&self.path, source, |path, source| LotError::Damaged { path, reason: source.to_string() })
    }
}
