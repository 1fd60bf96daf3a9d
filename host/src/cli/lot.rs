//! `accelcal lot`: certificates into the lot database, the lot's distributions and Cpk against a
//! spec file, and one board's calibrations by serial.

use std::path::{Path, PathBuf};

use super::args::{GroupBy, LotAction, LotArgs, RecordFormat};
use crate::certificate::{self, Certificate};
use crate::error::Error;
use crate::lot::queue::Queue;
use crate::lot::stations::Grouping;
use crate::lot::{self, Added, Lot, LotError, LotSummary, Spec};
use crate::records::{self, RunRecord};

/// Runs `accelcal lot`.
pub(super) fn lot(args: &LotArgs) -> Result<(), Error> {
    match &args.action {
        LotAction::Add { lot, certificates, station } => add_files(lot, certificates, station.as_deref()),
        LotAction::Sync { lot, queue, station } => sync(lot, queue.as_deref(), station.as_deref()),
        LotAction::Show { lot, spec, json, by: None } => show(lot, spec.as_deref(), *json),
        LotAction::Show { lot, spec, json, by: Some(by) } => show_by(lot, spec.as_deref(), *json, *by),
        LotAction::Export { lot, format, out, spec, serial } => {
            export(lot, *format, out, spec.as_deref(), serial.as_deref())
        }
        LotAction::Board { lot, serial, json } => {
            let certificates = Lot::open_existing(lot)?.board(serial)?;
            match json {
                true => println!("{}", serde_json::to_string_pretty(&certificates).unwrap_or_default()),
                false => print!("{}", lot::text::board(&certificates)),
            }
            Ok(())
        }
    }
}

/// Adds certificate files, one transaction each, once every one is checked against its hash and
/// names the serial the lot keys it by: a bad file among many adds none of them.
fn add_files(path: &Path, files: &[PathBuf], station: Option<&str>) -> Result<(), Error> {
    let checked: Vec<Certificate> = files.iter().map(|file| checked_for_lot(file)).collect::<Result<_, _>>()?;
    let mut lot = Lot::open_for_writing(path)?;
    if let Some(station) = station {
        lot.station = station.to_owned();
    }
    let bar = crate::terminal::counting("adding certificates {bar:30} {pos}/{len}", checked.len() as u64);
    let mut already = 0;
    for certificate in &checked {
        already += usize::from(lot.add(certificate)? == Added::AlreadyThere);
        bar.inc(1);
    }
    bar.finish_and_clear();
    println!(
        "{} added to {} ({already} already there)",
        checked.len() - already,
        lot::server::shown(&path.to_string_lossy()).display()
    );
    Ok(())
}

/// Uploads this station's queue to the lot's server; a refused file or a server that stopped
/// answering is an error, after what was sent is said.
fn sync(path: &Path, queue: Option<&Path>, station: Option<&str>) -> Result<(), Error> {
    let mut queue = match queue {
        Some(dir) => Queue::at(dir),
        None => Queue::of_station()?,
    };
    queue.station = station.map(str::to_owned);
    let synced = queue.send(path)?;
    println!(
        "{} sent to {} ({} already there), {} waiting in {}",
        synced.sent,
        lot::server::shown(&path.to_string_lossy()).display(),
        synced.already,
        synced.waiting,
        queue.dir.display()
    );
    for (file, why) in &synced.refused {
        eprintln!("refused and set aside as {}: {why}", file.display());
    }
    match (synced.stopped, synced.refused.is_empty()) {
        (Some(stopped), _) => Err(stopped.into()),
        (None, false) => {
            Err(LotError::RefusedInQueue { count: synced.refused.len(), dir: queue.dir.join("refused") }.into())
        }
        (None, true) => Ok(()),
    }
}

/// A certificate file checked against its hash and for the board serial the lot keys it by.
fn checked_for_lot(file: &Path) -> Result<Certificate, Error> {
    let certificate = certificate::check(file)?;
    match certificate.board.serial {
        Some(_) => Ok(certificate),
        None => Err(LotError::NoSerialIn { file: file.into() }.into()),
    }
}

/// Writes each certificate of the lot (or of one board) as a test executive's record in `out`.
fn export(
    path: &Path,
    format: RecordFormat,
    out: &Path,
    spec: Option<&Path>,
    serial: Option<&str>,
) -> Result<(), Error> {
    let spec = spec.map(Spec::load).transpose()?.unwrap_or_default();
    let all = Lot::open_existing(path)?.all()?;
    let chosen: Vec<_> = all.iter().filter(|(c, _)| serial.is_none() || c.board.serial.as_deref() == serial).collect();
    if let (true, Some(serial)) = (chosen.is_empty(), serial) {
        return Err(LotError::UnknownBoard { path: path.into(), serial: serial.into() }.into());
    }
    let unwritable = |source| Error::Lot(LotError::Records { dir: out.into(), source });
    std::fs::create_dir_all(out).map_err(unwritable)?;
    for (certificate, station) in &chosen {
        let run = RunRecord::of(certificate, station, &spec);
        let stem = format!("{}-{}", run.dut_id, &certificate.sha256[..12.min(certificate.sha256.len())]);
        let (name, text) = match format {
            RecordFormat::Openhtf => (format!("{stem}.openhtf.json"), records::openhtf::record(&run).to_string()),
            RecordFormat::Ocp => (format!("{stem}.ocp.jsonl"), records::ocp::artifacts(&run)),
        };
        crate::files::write_atomically(&out.join(name), text.as_bytes()).map_err(unwritable)?;
    }
    println!("{} records written to {}", chosen.len(), out.display());
    Ok(())
}

/// The spec at `spec_path` (none: no limits), its names checked against the certificates'.
fn spec_for(spec_path: Option<&Path>, certificates: &[&Certificate]) -> Result<Spec, Error> {
    let Some(spec_path) = spec_path else { return Ok(Spec::default()) };
    let spec = Spec::load(spec_path)?;
    spec.check_names(spec_path, certificates.iter().flat_map(|c| c.parameters.keys()))?;
    Ok(spec)
}

/// The lot by station or day, with the drifting stations, as text or JSON.
fn show_by(path: &Path, spec_path: Option<&Path>, json: bool, by: GroupBy) -> Result<(), Error> {
    let all = Lot::open_existing(path)?.all()?;
    let spec = spec_for(spec_path, &all.iter().map(|(c, _)| c).collect::<Vec<_>>())?;
    let (grouping, name) = match by {
        GroupBy::Station => (Grouping::Station, "station"),
        GroupBy::Day => (Grouping::Day, "day"),
    };
    let grouped = lot::stations::grouped(&all, grouping, &spec);
    match json {
        true => println!("{}", serde_json::to_string_pretty(&grouped).unwrap_or_default()),
        false => print!("{}", lot::text::grouped(&grouped, name)),
    }
    Ok(())
}

/// The lot's summary against the spec, as text or JSON.
fn show(path: &Path, spec_path: Option<&Path>, json: bool) -> Result<(), Error> {
    let latest = Lot::open_existing(path)?.latest()?;
    let spec = spec_for(spec_path, &latest.iter().collect::<Vec<_>>())?;
    let summary = LotSummary::of(&latest, &spec);
    match json {
        true => println!("{}", serde_json::to_string_pretty(&summary).unwrap_or_default()),
        false => print!("{}", lot::text::summary(&summary)),
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::sessions::adaptive as session;

    #[test]
    fn a_certificate_without_a_serial_among_others_adds_none_of_them_and_is_named() {
        let dir = std::env::temp_dir().join(format!("accelcal-cli-lot-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let (keyed, unkeyed, lot) = (dir.join("b1.json"), dir.join("stream.json"), dir.join("lot.sqlite"));
        let mut certificate = Certificate::issue(&session(1, 1.0, 2.8e-3)).unwrap();
        std::fs::write(&unkeyed, certificate.to_json()).unwrap();
        certificate.board.serial = Some("B1".into());
        std::fs::write(&keyed, certificate.resealed().to_json()).unwrap();
        let refused = add_files(&lot, &[keyed.clone(), unkeyed.clone()], None).unwrap_err().to_string();
        assert!(
            refused.contains(&*unkeyed.to_string_lossy()) && refused.contains("no certificate was added"),
            "{refused}"
        );
        assert!(!lot.exists(), "the lot was written before every certificate was checked");
        add_files(&lot, &[keyed], None).unwrap();
        let _ = std::fs::remove_dir_all(&dir);
    }
}
