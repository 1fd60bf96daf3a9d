//! `accelcal`: argument parsing and wiring only; the work is in the `accelcal` library.

use std::path::PathBuf;
use std::process::ExitCode;

use accelcal::commands::{self, CalibrateArgs};
use accelcal::connect::Target;
use accelcal::data::{Dataset, RowList};
use accelcal::fit::{self, FitOptions, ModelChoice};
use accelcal::report::{self, Comparison, FitJson};
use anyhow::Context;
use clap::{Args, Parser, Subcommand};
use shared::protocol::{Request, DEFAULT_CAPTURE_SECONDS};

/// Calibrates the accelerometer of an MPU-6050.
#[derive(Parser)]
#[command(version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

/// Which device to talk to.
#[derive(Args, Clone)]
struct Device {
    /// Serial port of the board (see `accelcal ports`), or of `accelcal sim --pty`.
    #[arg(long, conflicts_with = "sim")]
    port: Option<String>,
    /// A simulated board in this process (its flash lasts as long as the command).
    #[arg(long)]
    sim: bool,
    /// With --sim: seed of the simulated sensor's noise and of the hand's placement.
    #[arg(long, default_value_t = 1)]
    seed: u64,
}

impl Device {
    fn target(&self) -> anyhow::Result<Target> {
        match (&self.port, self.sim) {
            (Some(path), _) => Ok(Target::Port(path.clone())),
            (None, true) => Ok(Target::Simulated { seed: self.seed }),
            (None, false) => anyhow::bail!("which device? give --port PATH (see `accelcal ports`) or --sim"),
        }
    }
}

#[derive(Subcommand)]
enum Command {
    /// Fits a calibration to a calibration data file (CSV, see README).
    Fit {
        /// The data file.
        file: PathBuf,
        /// The model: auto (the richest the data supports, compared with the others),
        /// reference-norm12, linear12, ortho9, diag6 or six-position.
        #[arg(long, default_value = "auto")]
        model: ModelChoice,
        /// |gravity| in the output unit: 1 for data in g, 9.80665 (or the local value) for m/s^2.
        #[arg(long, default_value_t = 1.0)]
        g: f64,
        /// Largest tilt in degrees for a reading to count as one of the six faces.
        #[arg(long, default_value_t = FitOptions::default().face_tolerance_deg)]
        face_tolerance_deg: f64,
        /// Data rows to fit (1-based, e.g. 1-20); the others are held out and reported as test rows.
        #[arg(long)]
        rows: Option<RowList>,
        /// Data rows whose known orientation the fit uses (e.g. 1,10); the others count as |a| = g.
        #[arg(long)]
        reference_rows: Option<RowList>,
        /// Print one JSON object instead of the table.
        #[arg(long)]
        json: bool,
    },
    /// Lists serial ports, marking accelcal boards.
    Ports,
    /// Firmware, sensor, range, and the active and stored calibration.
    Info {
        #[command(flatten)]
        device: Device,
        /// Print one JSON object.
        #[arg(long)]
        json: bool,
    },
    /// The guided calibration: positions, captures, fit, upload, save, verification.
    Calibrate {
        #[command(flatten)]
        device: Device,
        /// Only the six faces, fitted on the chip.
        #[arg(long)]
        quick: bool,
        /// Seconds to average each position (5-20).
        #[arg(long, default_value_t = DEFAULT_CAPTURE_SECONDS)]
        seconds: u8,
        /// Fresh orientations to verify at.
        #[arg(long, default_value_t = 6)]
        verify: usize,
        /// Upload and save without asking.
        #[arg(long)]
        yes: bool,
        /// Print one JSON object (non-interactive with --sim).
        #[arg(long)]
        json: bool,
        /// Keep the session as PATH.json and PATH.csv.
        #[arg(long)]
        session: Option<PathBuf>,
        /// With --sim: how many degrees off the tool places the board, as a hand would.
        #[arg(long, default_value_t = 3.0)]
        sim_placement_deg: f64,
    },
    /// Captures one position into a session file.
    Capture {
        #[command(flatten)]
        device: Device,
        /// Session path without extension (PATH.json and PATH.csv are written).
        #[arg(long)]
        session: PathBuf,
        /// A name for the position.
        #[arg(long, default_value = "position")]
        name: String,
        /// Seconds to average (5-20).
        #[arg(long, default_value_t = DEFAULT_CAPTURE_SECONDS)]
        seconds: u8,
    },
    /// Uploads a calibration (from `download` or `fit --json` on data in g) and makes it active.
    Upload {
        #[command(flatten)]
        device: Device,
        /// The calibration JSON file.
        file: PathBuf,
        /// Also store it in flash.
        #[arg(long)]
        save: bool,
    },
    /// Stores the active calibration in flash.
    Save {
        #[command(flatten)]
        device: Device,
    },
    /// Prints the active (or stored) calibration as JSON.
    Download {
        #[command(flatten)]
        device: Device,
        /// The one in flash rather than the active one.
        #[arg(long)]
        stored: bool,
    },
    /// Erases the stored calibration; samples pass through uncorrected.
    Erase {
        #[command(flatten)]
        device: Device,
    },
    /// Checks the active calibration at fresh orientations.
    Verify {
        #[command(flatten)]
        device: Device,
        /// Orientations to check.
        #[arg(long, default_value_t = 4)]
        positions: usize,
    },
    /// Streams samples as CSV on stdout.
    Stream {
        #[command(flatten)]
        device: Device,
        /// Corrected on the chip (default: raw).
        #[arg(long)]
        calibrated: bool,
        /// Samples to stream.
        #[arg(long, default_value_t = 100)]
        count: u32,
        /// Samples per second (must divide the 100 Hz sample rate).
        #[arg(long, default_value_t = 10)]
        rate: u16,
    },
    /// Runs a simulated board on a pseudo-terminal; prints its path, then serves until killed.
    Sim {
        /// Serve on a pseudo-terminal (the only transport offered).
        #[arg(long, required = true)]
        pty: bool,
        /// Seed of the simulated sensor's noise.
        #[arg(long, default_value_t = 1)]
        seed: u64,
    },
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("accelcal: {error:#}");
            ExitCode::FAILURE
        }
    }
}

fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        Command::Fit { file, model, g, face_tolerance_deg, rows, reference_rows, json } => {
            anyhow::ensure!(g.is_finite() && g > 0.0, "--g must be a positive number, got {g}");
            let dataset = Dataset::from_path(&file, g).with_context(|| file.display().to_string())?;
            let (training_rows, reference_rows) = (rows.map(|r| r.0), reference_rows.map(|r| r.0));
            let options = FitOptions { g, face_tolerance_deg, training_rows, reference_rows };
            let fit = fit::fit(&dataset, model, &options)
                .with_context(|| format!("{}: cannot fit {model}", file.display()))?;
            let evaluation = fit::evaluate(&dataset, &fit.matrix, &fit.offset, g, &fit.lines_used);
            let comparison = (model == ModelChoice::Auto).then(|| Comparison::new(&dataset, &options));
            if json {
                let object = FitJson::new(&fit, &evaluation, g, comparison.as_ref());
                println!("{}", serde_json::to_string_pretty(&object)?);
            } else {
                print!("{}", report::human(&fit, &dataset, &evaluation, g));
                if let Some(comparison) = &comparison {
                    print!("{}", comparison.human());
                }
            }
        }
        Command::Ports => commands::ports()?,
        Command::Info { device, json } => commands::info(&device.target()?, json)?,
        Command::Calibrate { device, quick, seconds, verify, yes, json, session, sim_placement_deg } => {
            let args = CalibrateArgs {
                quick,
                seconds,
                verify_positions: verify,
                yes,
                json,
                session,
                placement_deg: sim_placement_deg,
                seed: device.seed,
            };
            commands::calibrate(&device.target()?, &args)?
        }
        Command::Capture { device, session, name, seconds } => {
            commands::capture(&device.target()?, &session, &name, seconds)?
        }
        Command::Upload { device, file, save } => commands::upload(&device.target()?, &file, save)?,
        Command::Save { device } => commands::simple(&device.target()?, Request::SaveCalibration, "saved")?,
        Command::Download { device, stored } => commands::download(&device.target()?, stored)?,
        Command::Erase { device } => {
            commands::simple(&device.target()?, Request::EraseCalibration, "stored calibration erased")?
        }
        Command::Verify { device, positions } => commands::verify(&device.target()?, positions, 3.0, device.seed)?,
        Command::Stream { device, calibrated, count, rate } => {
            commands::stream(&device.target()?, calibrated, count, rate)?
        }
        Command::Sim { pty: _, seed } => commands::sim_pty(seed)?,
    }
    Ok(())
}
