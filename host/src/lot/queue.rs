//! A station's own record of its certificates before the lot's server has them (issue 41): each
//! certificate is written to the station's queue folder first, named by its hash, and uploaded from
//! there. The upload is keyed by that hash, so a certificate sent again (after a station was killed
//! between the server's commit and the move below, say) adds nothing. One the server took moves to
//! `sent/` (the station keeps its records); one it did not take waits for the next upload or for
//! `accelcal lot sync`. A file in the queue whose hash no longer matches is refused, as `lot add`
//! refuses it, and set aside in `refused/`.

use std::path::{Path, PathBuf};

use super::{Added, Lot, LotError};
use crate::certificate::{self, Certificate};

/// Names the station's queue folder (default `~/.local/share/accelcal/lot-queue`).
pub const QUEUE_VARIABLE: &str = "ACCELCAL_LOT_QUEUE";

/// A station's queue folder.
pub struct Queue {
    pub dir: PathBuf,
    /// The station its certificates are recorded from, when not this process's ([`super::this_station`]).
    pub station: Option<String>,
}

/// What one upload of the queue did.
#[derive(Debug, Default)]
pub struct Synced {
    /// Certificates the server took.
    pub sent: usize,
    /// Certificates the server already held (the same hash): moved to `sent/`, not added again.
    pub already: usize,
    /// Files refused by their hash (altered or damaged), each with why, moved to `refused/`.
    pub refused: Vec<(PathBuf, String)>,
    /// Certificates still waiting, and why the upload stopped, when it did.
    pub waiting: usize,
    pub stopped: Option<LotError>,
}

impl Queue {
    /// The queue at `dir`.
    pub fn at(dir: &Path) -> Self {
        Queue { dir: dir.into(), station: None }
    }

    /// This station's queue: [`QUEUE_VARIABLE`], else `~/.local/share/accelcal/lot-queue`.
    pub fn of_station() -> Result<Self, LotError> {
        if let Some(dir) = std::env::var_os(QUEUE_VARIABLE).filter(|d| !d.is_empty()) {
            return Ok(Queue { dir: dir.into(), station: None });
        }
        let home = std::env::var_os("HOME").map(PathBuf::from).unwrap_or_else(|| ".".into());
        Ok(Queue { dir: home.join(".local/share/accelcal/lot-queue"), station: None })
    }

    /// Writes the certificate into the queue (atomically: a killed station leaves it whole or absent).
    pub fn keep(&self, certificate: &Certificate) -> Result<PathBuf, LotError> {
        let failed = |source| LotError::Queue { dir: self.dir.clone(), source };
        std::fs::create_dir_all(&self.dir).map_err(failed)?;
        let file = self.dir.join(format!("{}.certificate.json", certificate.sha256));
        crate::files::write_atomically(&file, certificate.to_json().as_bytes()).map_err(failed)?;
        Ok(file)
    }

    /// The certificate files waiting, by name.
    pub fn waiting(&self) -> Result<Vec<PathBuf>, LotError> {
        let entries = match std::fs::read_dir(&self.dir) {
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Vec::new()),
            entries => entries.map_err(|source| LotError::Queue { dir: self.dir.clone(), source })?,
        };
        let mut files: Vec<PathBuf> = entries
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.is_file() && p.to_string_lossy().ends_with(".certificate.json"))
            .collect();
        files.sort();
        Ok(files)
    }

    /// Uploads every certificate waiting to the lot at `place`, each checked against its hash first,
    /// until the server stops answering.
    pub fn send(&self, place: &Path) -> Result<Synced, LotError> {
        let waiting = self.waiting()?;
        let mut synced = Synced { waiting: waiting.len(), ..Synced::default() };
        if waiting.is_empty() {
            return Ok(synced);
        }
        let mut lot = match Lot::open_for_writing(place) {
            Ok(lot) => lot,
            Err(stopped) => return Ok(Synced { stopped: Some(stopped), ..synced }),
        };
        if let Some(station) = &self.station {
            lot.station.clone_from(station);
        }
        for file in waiting {
            let certificate = match certificate::check(&file) {
                Ok(certificate) => certificate,
                Err(refused) => {
                    synced.refused.push((self.set_aside(&file, "refused")?, refused.to_string()));
                    synced.waiting -= 1;
                    continue;
                }
            };
            match lot.add(&certificate) {
                Ok(Added::New) => synced.sent += 1,
                Ok(Added::AlreadyThere) => synced.already += 1,
                Err(stopped) => return Ok(Synced { stopped: Some(stopped), ..synced }),
            }
            self.set_aside(&file, "sent")?;
            synced.waiting -= 1;
        }
        Ok(synced)
    }

    /// Moves a queued file into the queue's `folder` (`sent`, `refused`); its new path.
    fn set_aside(&self, file: &Path, folder: &str) -> Result<PathBuf, LotError> {
        let failed = |source| LotError::Queue { dir: self.dir.clone(), source };
        let into = self.dir.join(folder);
        std::fs::create_dir_all(&into).map_err(failed)?;
        let moved = into.join(file.file_name().unwrap_or_default());
        std::fs::rename(file, &moved).map_err(failed)?;
        Ok(moved)
    }

    /// Keeps a certificate just issued and uploads the queue; what to tell the person (a server that
    /// does not answer leaves it waiting, which is no failure of the calibration).
    pub fn keep_and_send(&self, place: &Path, certificate: &Certificate) -> Result<String, LotError> {
        let kept = self.keep(certificate)?;
        let synced = self.send(place)?;
        let serial = certificate.board.serial.as_deref().unwrap_or("");
        Ok(match (&synced.stopped, kept.exists()) {
            (Some(why), true) => format!(
                "certificate of board {serial} kept in this station's queue {} ({} waiting): {why}",
                self.dir.display(),
                synced.waiting
            ),
            _ => format!(
                "certificate of board {serial} uploaded to the lot {}",
                super::server::shown(&place.to_string_lossy()).display()
            ),
        })
    }
}
