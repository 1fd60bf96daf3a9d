//! The command line's arguments (clap).

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};
use shared::protocol::DEFAULT_CAPTURE_SECONDS;

pub use super::device::Device;
pub use super::export::ExportArgs;
use super::overwrite::Overwrite;
pub use super::record::RecordArgs;
pub use super::report::ReportArgs;
use super::values::{placement_deg, rate_help, seconds, seconds_help, stream_rate, target_span_c};
use crate::data::RowList;
use crate::fit::ModelChoice;
use crate::limits::{FACE_TOLERANCE_DEG, MAX_VERIFY_POSITIONS};

/// Calibrates the accelerometer of an MPU-6050.
#[derive(Parser)]
#[command(name = "accelcal", version, about)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// `accelcal fit`.
#[derive(Args)]
pub struct FitArgs {
    /// The data file.
    pub file: PathBuf,
    /// The model: auto (the one that best predicts rows left out of its fit, compared with the others),
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
    #[command(flatten)]
    pub stream: SketchStreamArgs,
}

/// What a raw stream (a sketch's own log or port) may need said about it; each is found from the
/// stream where it can be.
#[derive(Args, Debug, Clone, Default)]
pub struct SketchStreamArgs {
    /// The unit of the stream's accelerometer values, when the stream leaves it unclear.
    #[arg(long, value_enum)]
    pub input_unit: Option<crate::stream::AccelUnit>,
    /// The unit of the stream's gyro values (counts of a range cannot be told from a resting gyro).
    #[arg(long, value_enum)]
    pub gyro_unit: Option<crate::stream::GyroUnit>,
}

impl SketchStreamArgs {
    /// The options for reading a stream, at `rate_hz` when one was given.
    pub fn options(&self, rate_hz: Option<f64>) -> crate::stream::StreamOptions {
        crate::stream::StreamOptions { accel_unit: self.input_unit, gyro_unit: self.gyro_unit, rate_hz }
    }
}

/// `accelcal calibrate`.
#[derive(Args, Clone)]
pub struct CalibrateArgs {
    #[command(flatten)]
    pub device: Device,
    /// On a board that prints its own stream: the file that keeps every line read (default: the
    /// session's SESSION.log); `accelcal fit` on it gives the same calibration.
    #[arg(long, value_name = "LOG")]
    pub stream_log: Option<PathBuf>,
    #[command(flatten)]
    pub replace: Overwrite,
    #[command(flatten)]
    pub stream: SketchStreamArgs,
    /// Ten positions (six faces, four corners), fitted on the chip: no fit on the host.
    #[arg(long)]
    pub quick: bool,
    #[arg(long, value_parser = seconds(), help = format!("{}, fixed; default: until its mean is known well \
          enough for --target-mg ({} with --quick)", seconds_help("Seconds to average each position"),
          crate::procedure::QUICK_CAPTURE_SECONDS))]
    pub seconds: Option<u8>,
    /// Fresh orientations to verify at (1-16); default 6 with fixed lengths, else 3, each as long as the target needs.
    #[arg(long, value_parser = clap::value_parser!(u8).range(1..=MAX_VERIFY_POSITIONS))]
    pub verify: Option<u8>,
    #[command(flatten)]
    pub length: super::length::LengthArgs,
    /// Upload and save without asking.
    #[arg(long)]
    pub yes: bool,
    /// Print one JSON object (non-interactive with --sim).
    #[arg(long)]
    pub json: bool,
    /// Keep the session as PATH.json and PATH.csv, written after every capture (with --port the
    /// default is accelcal-session-TIME in the current directory), and its report as PATH.html.
    #[arg(long, conflicts_with = "resume")]
    pub session: Option<PathBuf>,
    /// Continue the session SESSION.json (same board, range and filter) with the positions it lacks.
    #[arg(long, value_name = "SESSION")]
    pub resume: Option<PathBuf>,
    /// Add the board's certificate to this lot database (one SQLite file, created when new).
    #[arg(long, value_name = "LOT")]
    pub lot: Option<PathBuf>,
    /// On a board that prints its own stream: its serial or label, which its certificate and the
    /// lot key it by (a board running accelcal's firmware reports its own).
    #[arg(long, value_name = "LABEL", value_parser = clap::builder::NonEmptyStringValueParser::new())]
    pub serial: Option<String>,
    /// With --sim: how many degrees off the tool places the board, as a hand would (0-8).
    #[arg(long, default_value_t = 3.0, value_parser = placement_deg)]
    pub sim_placement_deg: f64,
    /// With --sim: the seed of the tool's hand (its placement errors and fresh orientations); default
    /// --seed. On a fixture one hand turns every board.
    #[arg(long)]
    pub sim_hand_seed: Option<u64>,
    #[command(flatten)]
    pub fixture: super::fixture::FixtureArgs,
}

/// `accelcal thermal`.
#[derive(Args)]
pub struct ThermalArgs {
    #[command(flatten)]
    pub device: Device,
    /// Stop learning once the temperature has spanned this many degC (10-100: a temperature model
    /// needs at least 10).
    #[arg(long, default_value_t = 34.0, value_parser = target_span_c)]
    pub target_span_c: f64,
    /// With --port: keep the learned bins in this JSON file after every capture, and go on from it
    /// when it exists (default: accelcal-thermal-TIME.json in the current directory).
    #[arg(long, value_name = "PATH")]
    pub bins: Option<PathBuf>,
    /// With --sim: fresh orientations verified at each temperature (corners of a turned cube, 1-8).
    #[arg(long, default_value_t = 8, value_parser = clap::value_parser!(u8).range(1..=8))]
    pub verify: u8,
    /// Print one JSON object (non-interactive).
    #[arg(long)]
    pub json: bool,
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
    #[arg(long, default_value_t = DEFAULT_CAPTURE_SECONDS, value_parser = seconds(), help = seconds_help("Seconds to average"))]
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
    /// Samples to stream (1 or more; to stop early, close the output, e.g. `| head`).
    #[arg(long, default_value_t = 100, value_parser = clap::value_parser!(u32).range(1..))]
    pub count: u32,
    #[arg(long, default_value_t = 10, value_parser = stream_rate, help = rate_help())]
    pub rate: u16,
}

/// `accelcal noise`.
#[derive(Args)]
pub struct NoiseArgs {
    /// The recording: .npy from `accelcal record`, or CSV (ax_g ... gz_dps) from `accelcal stream`.
    pub file: PathBuf,
    /// Samples per second of a CSV file without a time_s column (default 1000); a .npy recording
    /// and a `stream` CSV (its time_s) name their own, which a given rate must agree with.
    #[arg(long)]
    pub rate: Option<f64>,
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
    /// Fits a calibration to a calibration data file (CSV, see docs/guide.md).
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
        /// Also dump the sensor's registers 0x00-0x7F (to paste into a report of a part accelcal does not know).
        #[arg(long)]
        registers: bool,
    },
    /// The datasheet self-test of the sensor: each axis's response against its factory trim, beside the board's previous one.
    Selftest(super::selftest::SelftestArgs),
    /// The guided calibration: positions, captures, fit, upload, save, verification.
    Calibrate(CalibrateArgs),
    /// Writes a session's report: one self-contained HTML page with plots (and text or JSON on stdout).
    Report(ReportArgs),
    /// Captures one position into a session file.
    Capture(CaptureArgs),
    /// A session's calibration certificate (uncertainties at k = 2, hashed), or the check of one.
    Certificate(super::certificate::CertificateArgs),
    /// The lot database: every board's certificates in one SQLite file, the lot's distributions and Cpk.
    Lot(super::lot::LotArgs),
    /// N calibrations of one simulated board with a power cycle between them: each parameter's spread
    /// beside the standard error the sessions predicted.
    Repeat(super::repeat::RepeatArgs),
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
        /// Orientations to check (1-16).
        #[arg(long, default_value_t = 4, value_parser = clap::value_parser!(u8).range(1..=MAX_VERIFY_POSITIONS))]
        positions: u8,
    },
    /// Streams samples as CSV on stdout.
    Stream(StreamArgs),
    /// Learns how the sensor drifts with temperature and adds the temperature model to the active
    /// calibration (with --sim: the whole simulated story, verified at 15-45 degC).
    Thermal(ThermalArgs),
    /// Records raw samples at the sensor's full rate into a .npy file, with a progress bar.
    Record(RecordArgs),
    /// The calibration in another program's format (C, Rust, Fusion, ArduPilot, PX4, ...; see --to).
    Export(ExportArgs),
    /// Allan deviation and noise terms (white noise, bias instability, random walk) of a still recording.
    Noise(NoiseArgs),
    /// Runs a simulated board on a pseudo-terminal; prints its path, then serves until killed.
    Sim {
        /// Serve on a pseudo-terminal (the only transport offered).
        #[arg(long, required_unless_present = "sketch")]
        pty: bool,
        /// Instead of an accelcal board, a board running this sketch: a simulated person's
        /// three-minute session as it prints it (with --pty at its own pace, else all at once on stdout).
        #[arg(long, value_enum)]
        sketch: Option<crate::sim::sketch::Sketch>,
        /// Seed of the simulated sensor's noise.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Fast-forward simulated time while the board works (a 10 s capture takes a fraction of
        /// a second); by default it runs in real time, as a board does.
        #[arg(long)]
        fast: bool,
        /// Instead of the firmware library in this process, the real Pico binary from this UF2
        /// (dist/accelcal-pico.uf2) in the rp2040js emulator, the simulated sensor on its I2C bus
        /// (needs Node.js and `npm ci` in boards/pico/emulator; docs/boards.md).
        #[arg(long, value_name = "UF2", conflicts_with_all = ["sketch", "fast"])]
        pico: Option<std::path::PathBuf>,
    },
}
