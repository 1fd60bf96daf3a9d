//! `accelcal lot`: certificates into the lot database, the lot's distributions and Cpk against a
//! spec file, and one board's calibrations by serial.

use std::path::{Path, PathBuf};
use std::time::Duration;

use clap::{Args, Subcommand};
use indicatif::{ProgressBar, ProgressStyle};

use crate::certificate::{self, Certificate};
use crate::error::Error;
use crate::lot::{self, Added, Lot, LotSummary, Spec};

/// `accelcal lot`.
#[derive(Args)]
pub struct LotArgs {
    #[command(subcommand)]
    pub action: LotAction,
}

/// What to do with a lot database.
#[derive(Subcommand)]
pub enum LotAction {
    /// Adds certificates (each checked against its hash) to the lot, creating the file when new.
    Add {
        /// The lot database (one SQLite file).
        lot: PathBuf,
        /// Certificate files (PATH.certificate.json written by calibrate --session).
        #[arg(required = true)]
        certificates: Vec<PathBuf>,
    },
    /// Each parameter's distribution over the lot (each board's latest certificate), Cpk against the
    /// spec's limits and the boards outside them.
    Show {
        lot: PathBuf,
        /// The spec file: TOML, `[limits.NAME]` with `low` and/or `high` in the certificate's units.
        #[arg(long)]
        spec: Option<PathBuf>,
        /// Print one JSON object.
        #[arg(long)]
        json: bool,
    },
    /// Every calibration of one board, by its serial.
    Board {
        lot: PathBuf,
        serial: String,
        /// Print the certificates as a JSON array.
        #[arg(long)]
        json: bool,
    },
}

/// The environment variable that makes every write pause inside its transaction (seconds): only
/// for the tests that kill a writer, or read beside one, mid-transaction.
pub const PAUSE_IN_WRITE_VARIABLE: &str = "ACCELCAL_TEST_LOT_PAUSE_S";

/// Runs `accelcal lot`.
pub(super) fn lot(args: &LotArgs) -> Result<(), Error> {
    match &args.action {
        LotAction::Add { lot, certificates } => add_files(lot, certificates),
        LotAction::Show { lot, spec, json } => show(lot, spec.as_deref(), *json),
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

/// Adds certificate files, each checked against its hash first, one transaction each.
fn add_files(path: &Path, files: &[PathBuf]) -> Result<(), Error> {
    let checked: Vec<Certificate> = files.iter().map(|file| certificate::check(file)).collect::<Result<_, _>>()?;
    let mut lot = open_for_writing(path)?;
    let bar = ProgressBar::new(checked.len() as u64).with_style(
        ProgressStyle::with_template("adding certificates {bar:30} {pos}/{len}")
            .unwrap_or(ProgressStyle::default_bar()),
    );
    let mut already = 0;
    for certificate in &checked {
        already += usize::from(lot.add(certificate)? == Added::AlreadyThere);
        bar.inc(1);
    }
    bar.finish_and_clear();
    println!("{} added to {} ({already} already there)", checked.len() - already, path.display());
    Ok(())
}

/// Opens the lot for writing, with the test pause when its variable is set.
pub(super) fn open_for_writing(path: &Path) -> Result<Lot, Error> {
    let mut lot = Lot::create_or_open(path)?;
    lot.pause_in_write =
        std::env::var(PAUSE_IN_WRITE_VARIABLE).ok().and_then(|s| s.parse().ok()).map(Duration::from_secs_f64);
    Ok(lot)
}

/// Adds one freshly issued certificate to the lot and says so.
pub(super) fn add_issued(path: &Path, certificate: &Certificate) -> Result<String, Error> {
    open_for_writing(path)?.add(certificate)?;
    let serial = certificate.board.serial.as_deref().unwrap_or("");
    Ok(format!("certificate of board {serial} added to the lot {}", path.display()))
}

/// The lot's summary against the spec, as text or JSON.
fn show(path: &Path, spec_path: Option<&Path>, json: bool) -> Result<(), Error> {
    let latest = Lot::open_existing(path)?.latest()?;
    let spec = match spec_path {
        Some(spec_path) => {
            let spec = Spec::load(spec_path)?;
            spec.check_names(spec_path, latest.iter().flat_map(|c| c.parameters.keys()))?;
            spec
        }
        None => Spec::default(),
    };
    let summary = LotSummary::of(&latest, &spec);
    match json {
        true => println!("{}", serde_json::to_string_pretty(&summary).unwrap_or_default()),
        false => print!("{}", lot::text::summary(&summary)),
    }
    Ok(())
}
