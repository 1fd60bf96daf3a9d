//! The command line's arguments (clap).

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};
use shared::protocol::{SensorConfig, DEFAULT_CAPTURE_SECONDS, MAX_CAPTURE_SECONDS, MIN_CAPTURE_SECONDS};

use crate::data::RowList;
use crate::fit::ModelChoice;
use crate::limits::FACE_TOLERANCE_DEG;

/// Calibrates the accelerometer of an MPU-6050.
#[derive(Parser)]
#[command(name = "accelcal", version, about)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// Which device to talk to.
#[derive(Args, Clone)]
pub struct Device {
    /// Serial port of the board (see `accelcal ports`), or of `accelcal sim --pty`.
    #[arg(long, conflicts_with = "sim")]
    pub port: Option<String>,
    /// A simulated board in this process (its flash lasts as long as the command).
    #[arg(long)]
    pub sim: bool,
    /// With --sim: seed of the simulated sensor's noise and of the hand's placement.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
}

/// `accelcal fit`.
#[derive(Args)]
pub struct FitArgs {
    /// The data file.
    pub file: PathBuf,
    /// The model: auto (the richest the data supports, compared with the others),
    /// reference-norm12, linear12, ortho9, diag6 or six-position.
    #[arg(long, default_value = "auto")]
    pub model: ModelChoice,
    /// |gravity| in the output unit: 1 for data in g, 9.80665 (or the local value) for m/s^2.
    #[arg(long, default_value_t = 1.0)]
    pub g: f64,
    /// Largest tilt in degrees for a reading to count as one of the six faces.
    #[arg(long, default_value_t = FACE_TOLERANCE_DEG)]
    pub face_tolerance_deg: f64,
    /// Data rows to fit (1-based, e.g. 1-20); the others are held out and reported as test rows.
    #[arg(long)]
    pub rows: Option<RowList>,
    /// Data rows whose known orientation the fit uses (e.g. 1,10); the others count as |a| = g.
    #[arg(long)]
    pub reference_rows: Option<RowList>,
    /// Print one JSON object instead of the table.
    #[arg(long)]
    pub json: bool,
}

/// `accelcal calibrate`.
#[derive(Args)]
pub struct CalibrateArgs {
    #[command(flatten)]
    pub device: Device,
    /// Only the six faces, fitted on the chip.
    #[arg(long)]
    pub quick: bool,
    #[arg(long, default_value_t = DEFAULT_CAPTURE_SECONDS, help = seconds_help("Seconds to average each position"))]
    pub seconds: u8,
    /// Fresh orientations to verify at.
    #[arg(long, default_value_t = 6)]
    pub verify: usize,
    /// Upload and save without asking.
    #[arg(long)]
    pub yes: bool,
    /// Print one JSON object (non-interactive with --sim).
    #[arg(long)]
    pub json: bool,
    /// Keep the session as PATH.json and PATH.csv.
    #[arg(long)]
    pub session: Option<PathBuf>,
    /// With --sim: how many degrees off the tool places the board, as a hand would.
    #[arg(long, default_value_t = 3.0)]
    pub sim_placement_deg: f64,
}

/// `accelcal capture`.
#[derive(Args)]
pub struct CaptureArgs {
    #[command(flatten)]
    pub device: Device,
    /// Session path without extension (PATH.json and PATH.csv are written).
    #[arg(long)]
    pub session: PathBuf,
    /// A name for the position (a face or corner name such as +X or +X+Y+Z records that orientation).
    #[arg(long, default_value = "position")]
    pub name: String,
    #[arg(long, default_value_t = DEFAULT_CAPTURE_SECONDS, help = seconds_help("Seconds to average"))]
    pub seconds: u8,
}

/// `accelcal stream`.
#[derive(Args)]
pub struct StreamArgs {
    #[command(flatten)]
    pub device: Device,
    /// Corrected on the chip (default: raw).
    #[arg(long)]
    pub calibrated: bool,
    /// Samples to stream.
    #[arg(long, default_value_t = 100)]
    pub count: u32,
    #[arg(long, default_value_t = 10, help = rate_help())]
    pub rate: u16,
}

/// `accelcal noise`.
#[derive(Args)]
pub struct NoiseArgs {
    /// The recording (CSV with ax_g,ay_g,az_g,gx_dps,gy_dps,gz_dps, as `accelcal stream` writes).
    pub file: PathBuf,
    /// Samples per second of the recording.
    #[arg(long, default_value_t = 1000.0)]
    pub rate: f64,
    /// Print one JSON object instead of the table.
    #[arg(long)]
    pub json: bool,
    /// Also draw the deviation curves as an SVG file.
    #[arg(long)]
    pub plot: Option<PathBuf>,
}

/// The commands of `accelcal`.
#[derive(Subcommand)]
pub enum Command {
    /// Fits a calibration to a calibration data file (CSV, see README).
    Fit(FitArgs),
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
    Calibrate(CalibrateArgs),
    /// Captures one position into a session file.
    Capture(CaptureArgs),
    /// Uploads a calibration (from `download`, `calibrate --json`, or `fit --json` on data in g) and makes it active.
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
    Stream(StreamArgs),
    /// Allan deviation and noise terms (white noise, bias instability, random walk) of a still recording.
    Noise(NoiseArgs),
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

/// Help for a capture length, with the limits the device accepts.
fn seconds_help(what: &str) -> String {
    format!("{what} ({MIN_CAPTURE_SECONDS}-{MAX_CAPTURE_SECONDS})")
}

/// Help for a stream rate, with the sample rate it must divide.
fn rate_help() -> String {
    format!("Samples per second (must divide the {} Hz sample rate)", SensorConfig::default().sample_rate_hz)
}
