//! Every read of the lot re-checks what it is about to show (issue 40): SQLite's own integrity check
//! (a file's), each stored certificate against its hash and against the serial and date it is keyed
//! by, and the `parameters` rows against the certificates they come from. A lot that was altered or
//! damaged, in a file or on a server, is refused naming the board, never shown with a changed figure.

use std::collections::BTreeMap;

use super::schema::{ParameterRow, Stored};
use super::{file, server, Backend, Lot, LotError};
use crate::certificate::{digest_of, Certificate};

impl Lot {
    /// Every certificate of the lot with its station, by serial, then date, then the order added;
    /// each checked.
    pub(super) fn verified(&self) -> Result<Vec<(Certificate, String)>, LotError> {
        match self.integrity()?.as_slice() {
            [ok] if ok == "ok" => {}
            found => return Err(self.damaged(format!("SQLite's integrity check found: {}", found.join("; ")))),
        }
        let (mut stored, rows) = self.rows()?;
        // NOTE: sorted here, not by the SQL: the two dialects collate text differently.
        stored.sort_by(|a, b| (&a.serial, &a.date_utc, a.id).cmp(&(&b.serial, &b.date_utc, b.id)));
        let mut parameters: BTreeMap<i64, BTreeMap<String, ParameterRow>> = BTreeMap::new();
        for (id, name, values) in rows {
            parameters.entry(id).or_default().insert(name, values);
        }
        let mut certificates = Vec::new();
        for stored in stored {
            let certificate = self.checked(&stored)?;
            let rows = parameters.remove(&stored.id).unwrap_or_default();
            self.check_parameters(&stored, &certificate, &rows)?;
            certificates.push((certificate, stored.station));
        }
        match parameters.keys().next() {
            Some(id) => Err(self.damaged(format!("parameter rows of certificate {id}, which the lot does not hold"))),
            None => Ok(certificates),
        }
    }

    /// What SQLite's integrity check finds in a file ("ok" when intact); a server's lot is "ok".
    pub(super) fn integrity(&self) -> Result<Vec<String>, LotError> {
        match &self.backend {
            Backend::File(connection) => file::integrity(connection, &self.path),
            Backend::Server(_) => Ok(vec!["ok".to_owned()]),
        }
    }

    /// The `certificates` rows and the `parameters` rows, as stored.
    #[allow(clippy::type_complexity)]
    fn rows(&self) -> Result<(Vec<Stored>, Vec<(i64, String, ParameterRow)>), LotError> {
        match &self.backend {
            Backend::File(connection) => {
                Ok((file::stored(connection, &self.path, self.version)?, file::parameter_rows(connection, &self.path)?))
            }
            Backend::Server(client) => {
                let client = &mut client.borrow_mut();
                Ok((server::stored(client, &self.path)?, server::parameter_rows(client, &self.path)?))
            }
        }
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
}
