//! The command line's arguments (clap).

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};
use shared::protocol::DEFAULT_CAPTURE_SECONDS;

use super::values::{
    baud, placement_deg, pull, rate_help, seconds, seconds_help, stream_rate, target_mg, target_span_c, turn_on_bias_mg,
};
use crate::data::RowList;
use crate::export::Target;
use crate::fit::ModelChoice;
use crate::limits::{
    DEFAULT_TARGET_MG, FACE_TOLERANCE_DEG, MAX_BOARDS, MAX_RECORD_SECONDS, MAX_VERIFY_POSITIONS, QUICK_TARGET_MG,
};
use crate::link::port::DEFAULT_BAUD;
use crate::sim::Pull;
use crate::sim::{FaultyAxis, SimPartChoice, SimSensor};

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
    #[arg(long, value_parser = super::named::named::<crate::stream::AccelUnit>())]
    pub input_unit: Option<crate::stream::AccelUnit>,
    /// The unit of the stream's gyro values (counts of a range cannot be told from a resting gyro).
    #[arg(long, value_parser = super::named::named::<crate::stream::GyroUnit>())]
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
    /// Ten positions (six faces, four corners) of a fixed length, fitted on the chip: no fit on the
    /// host. For checking the chip's own fit: slower and less exact than the default.
    #[arg(long)]
    pub chip_fit: bool,
    #[arg(long, value_parser = seconds(), help = format!("{}, fixed; default: until its mean is known well \
          enough for --target-mg ({} with --chip-fit)", seconds_help("Seconds to average each position"),
          crate::procedure::QUICK_CAPTURE_SECONDS))]
    pub seconds: Option<u8>,
    /// Fresh orientations to verify at (1-16); default 6 with fixed lengths, else 3, each as long as the target needs.
    #[arg(long, value_parser = clap::value_parser!(u8).range(1..=MAX_VERIFY_POSITIONS))]
    pub verify: Option<u8>,
    #[command(flatten)]
    pub length: LengthArgs,
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
    /// Add the board's certificate to this lot database: one SQLite file (created when new), or a
    /// server, postgres://USER@HOST/DB, through this station's queue (ACCELCAL_LOT_QUEUE).
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
    pub fixture: FixtureArgs,
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
    Selftest(SelftestArgs),
    /// The guided calibration: positions, captures, fit, upload, save, verification.
    Calibrate(CalibrateArgs),
    /// Writes a session's report: one self-contained HTML page with plots (and text or JSON on stdout).
    Report(ReportArgs),
    /// Captures one position into a session file.
    Capture(CaptureArgs),
    /// A session's calibration certificate (uncertainties at k = 2, hashed), or the check of one.
    Certificate(CertificateArgs),
    /// The lot database: every board's certificates in one SQLite file, the lot's distributions and Cpk.
    Lot(LotArgs),
    /// N calibrations of one simulated board with a power cycle between them: each parameter's spread
    /// beside the standard error the sessions predicted.
    Repeat(RepeatArgs),
    /// Uploads a calibration (from `download`, `calibrate --json`, `fit --json` on data in g, or a session's SESSION.json, fitted as `export` fits it) and makes it active.
    Upload {
        #[command(flatten)]
        device: Device,
        /// The calibration JSON file, or a session file.
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
    /// Serves the web page (built by `cargo xtask web`) on localhost, for a browser with Web Serial.
    Web {
        /// The page's folder.
        #[arg(long, default_value = crate::web::BUILT_PAGE)]
        dir: PathBuf,
        /// The port on 127.0.0.1 (0: a free one).
        #[arg(long, default_value_t = 8037)]
        port: u16,
    },
    /// Runs a simulated board on a pseudo-terminal; prints its path, then serves until killed.
    Sim {
        /// Serve on a pseudo-terminal (the only transport offered).
        #[arg(long, required_unless_present = "sketch")]
        pty: bool,
        /// Instead of an accelcal board, a board running this sketch: a simulated person's
        /// three-minute session as it prints it (with --pty at its own pace, else all at once on stdout).
        #[arg(long, value_parser = super::named::named::<crate::sim::sketch::Sketch>())]
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

/// `accelcal certificate`.
#[derive(Args)]
pub struct CertificateArgs {
    #[command(subcommand)]
    pub action: CertificateAction,
}

/// What to do with a certificate.
#[derive(Subcommand)]
pub enum CertificateAction {
    /// Issues the certificate of a session (PATH.certificate.json and PATH.certificate.html beside it).
    Issue {
        /// The session file (PATH.json written by calibrate --session).
        session: PathBuf,
        /// Print the certificate as JSON too.
        #[arg(long)]
        json: bool,
        #[command(flatten)]
        replace: Overwrite,
    },
    /// Checks that a certificate file is unchanged since it was issued (its SHA-256).
    Verify {
        /// The certificate's .json file.
        file: PathBuf,
    },
}

/// Which device to talk to.
#[derive(Args, Clone)]
pub struct Device {
    /// Serial port of the board (see `accelcal ports`), or of `accelcal sim --pty`; or the board's
    /// serial number as `accelcal ports` shows it. Without --port or --sim: the one accelcal board
    /// plugged in (by its USB ids, or by its handshake on a USB port of another identity).
    #[arg(long, conflicts_with = "sim")]
    pub port: Option<String>,
    /// With --port: the baud rate of a UART bridge (the sketch's `Serial.begin`); USB serial ignores it.
    #[arg(long, default_value_t = DEFAULT_BAUD, value_parser = baud, conflicts_with = "sim")]
    pub baud: u32,
    /// A simulated board in this process (its flash lasts as long as the command).
    #[arg(long)]
    pub sim: bool,
    /// With --sim: seed of the simulated sensor's noise and of the hand's placement.
    #[arg(long, default_value_t = 1, conflicts_with = "port")]
    pub seed: u64,
    /// With --sim: the simulated sensor, realistic (warming and drifting; the default for one board),
    /// settled (one temperature) or drawn (realistic, a part drawn by the seed from the datasheet's
    /// spreads; the default for `calibrate --boards N`).
    #[arg(long, value_enum, conflicts_with = "port")]
    pub sim_sensor: Option<SimSensor>,
    /// With --sim: the simulated part (its register map, temperature formula and self-test).
    #[arg(long, value_enum, default_value_t = SimPartChoice::Mpu6050, conflicts_with = "port")]
    pub sim_part: SimPartChoice,
    /// With --sim: this axis' self-test response is 20 % off its factory trim.
    #[arg(long, value_enum, conflicts_with = "port")]
    pub sim_faulty_axis: Option<FaultyAxis>,
}

/// `accelcal export`.
#[derive(Args)]
pub struct ExportArgs {
    /// The calibration: what `calibrate --json`, `fit --json` (in g), `download` or a session (SESSION.json) wrote; leave it out with --port or --sim for the board's active calibration.
    #[arg(required_unless_present_any = ["port", "sim"], conflicts_with_all = ["port", "sim"])]
    pub calibration: Option<PathBuf>,
    /// The format (each says what of the calibration it carries).
    #[arg(long, value_parser = super::named::named::<Target>())]
    pub to: Target,
    /// The file to write (default: stdout; the binary adafruit-eeprom needs a file).
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// The noise report (`accelcal noise RECORDING --json`) whose terms go into the kalibr imu.yaml.
    #[arg(long, value_name = "NOISE.json")]
    pub noise: Option<PathBuf>,
    #[command(flatten)]
    pub device: Device,
    #[command(flatten)]
    pub replace: Overwrite,
}

/// `calibrate`'s boards on one fixture.
#[derive(Args, Clone, Debug)]
pub struct FixtureArgs {
    /// With --sim: how many simulated boards one fixture holds, calibrated together by one hand, each
    /// its own part (seeds --seed, --seed + 1, ...; --sim-sensor drawn unless given).
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u16).range(1..=MAX_BOARDS), conflicts_with = "port")]
    pub boards: u16,
    /// Several boards on one fixture, calibrated together: their ports (or serial numbers), comma-separated.
    #[arg(long, value_delimiter = ',', num_args = 1.., conflicts_with_all = ["sim", "port"])]
    pub ports: Vec<String>,
    /// Every accelcal board plugged in, calibrated together on one fixture.
    #[arg(long, conflicts_with_all = ["sim", "port", "ports"])]
    pub all_boards: bool,
    /// With --sim --boards: board K's cable is pulled right after the fixture's N-th turn (K:N, from 1),
    /// to see a board fail while the others go on.
    #[arg(long, value_name = "K:N", value_parser = pull, requires = "boards")]
    pub sim_pull: Option<Pull>,
}

/// `calibrate`'s target and noise.
#[derive(Args, Clone, Debug)]
pub struct LengthArgs {
    #[arg(long, value_parser = target_mg, help = format!("The | |a| - 1 g | error wanted at a fresh \
          orientation, in mg (0.05-10): positions stop when their mean is known well enough for it, the \
          session when the fit predicts it [default: {DEFAULT_TARGET_MG}; {QUICK_TARGET_MG} with --quick]"))]
    pub target_mg: Option<f64>,
    /// A shorter session for a looser target: --target-mg 2 (measured on the simulated board: 31 s of
    /// board time against 56 s for the default 0.2 mg, and the 2 mg reached at every seed tried).
    #[arg(long, conflicts_with = "target_mg")]
    pub quick: bool,
    /// A noise report (`accelcal noise RECORDING --json`): each capture's length from its white
    /// noise instead of from the scatter the board measures during the capture.
    #[arg(long, value_name = "NOISE.json")]
    pub noise_report: Option<PathBuf>,
}

/// A test executive's record format (`lot export --format`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum RecordFormat {
    /// OpenHTF's JSON test record (`TestRecord` -> phases -> measurements), one `.openhtf.json` per certificate.
    Openhtf,
    /// OCP Test & Validation output artifacts, one JSON object a line, one `.ocp.jsonl` per certificate.
    Ocp,
}

/// How `lot show --by` groups the boards.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum GroupBy {
    /// The station that uploaded each board's latest certificate.
    Station,
    /// The UTC day of each board's latest calibration.
    Day,
}

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
        /// The lot database: one SQLite file, or a server's postgres://USER@HOST[:PORT]/DB.
        lot: PathBuf,
        /// The station the certificates are recorded from (default: ACCELCAL_STATION, else the host name).
        #[arg(long)]
        station: Option<String>,
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
        /// Each station's or each day's boards apart, with the stations that drift from the others.
        #[arg(long, value_enum)]
        by: Option<GroupBy>,
    },
    /// Uploads the certificates waiting in this station's queue to the lot's server (each once, by
    /// its hash); what the server did not take waits for the next sync.
    Sync {
        /// The lot's server, postgres://USER@HOST[:PORT]/DB.
        lot: PathBuf,
        /// The station's queue folder (default: ACCELCAL_LOT_QUEUE, else ~/.local/share/accelcal/lot-queue).
        #[arg(long)]
        queue: Option<PathBuf>,
        /// The station the certificates are recorded from (default: ACCELCAL_STATION, else the host name).
        #[arg(long)]
        station: Option<String>,
    },
    /// Each certificate of the lot as the factory's test executive reads a test run: an OpenHTF JSON
    /// test record or OCP Test & Validation line-delimited JSON artifacts, one file per certificate.
    Export {
        lot: PathBuf,
        /// The record's format.
        #[arg(long, value_enum)]
        format: RecordFormat,
        /// The folder the records are written to (created when new).
        #[arg(long)]
        out: PathBuf,
        /// The spec file whose limits become each measurement's validators.
        #[arg(long)]
        spec: Option<PathBuf>,
        /// Only this board's certificates.
        #[arg(long)]
        serial: Option<String>,
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

/// `accelcal record`.
#[derive(Args)]
pub struct RecordArgs {
    #[command(flatten)]
    pub device: Device,
    /// The recording to write (NumPy .npy; `np.load(FILE)` in Python).
    #[arg(short, long)]
    pub output: PathBuf,
    /// How long to record, in seconds.
    #[arg(long, default_value_t = 60, value_parser = clap::value_parser!(u32).range(1..=MAX_RECORD_SECONDS))]
    pub seconds: u32,
    /// The sensor's sample rate, every sample recorded (must divide 1000 Hz).
    #[arg(long, default_value_t = 1000, value_parser = clap::value_parser!(u16).range(1..=1000))]
    pub rate: u16,
    #[command(flatten)]
    pub replace: Overwrite,
}

/// `accelcal repeat`.
#[derive(Args)]
pub struct RepeatArgs {
    /// Calibrations of the board (2-1000), each after a power cycle.
    #[arg(value_parser = clap::value_parser!(u16).range(2..=1000))]
    pub sessions: u16,
    #[command(flatten)]
    pub device: Device,
    /// With --sim: the turn-on bias repeatability to inject, the standard deviation of each axis'
    /// offset from one power-on to the next, in mg (0-50).
    #[arg(long, default_value_t = 0.0, value_parser = turn_on_bias_mg)]
    pub sim_turn_on_bias_mg: f64,
    /// Print one JSON object.
    #[arg(long)]
    pub json: bool,
}

/// `accelcal report`.
#[derive(Args)]
pub struct ReportArgs {
    /// The session file (PATH.json written by calibrate --session or capture).
    pub session: PathBuf,
    /// Where to write the HTML page (default: beside the session, PATH.html).
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// Print the report as one JSON object instead of text (the page is written only with -o).
    #[arg(long)]
    pub json: bool,
    /// Add the board's temperature model and its bins (the output of `accelcal thermal --json`).
    #[arg(long, value_name = "THERMAL.json")]
    pub thermal: Option<PathBuf>,
    /// Add the board's Allan deviation (the output of `accelcal noise --json`, or a recording).
    #[arg(long, value_name = "NOISE.json")]
    pub noise: Option<PathBuf>,
}

/// `accelcal selftest`.
#[derive(Args)]
pub struct SelftestArgs {
    #[command(flatten)]
    pub device: Device,
    /// Print one JSON object.
    #[arg(long)]
    pub json: bool,
    /// The folder that keeps each board's self-tests (`selftest-SERIAL.json`); a real board's go to
    /// $XDG_DATA_HOME/accelcal (~/.local/share/accelcal) unless given; a simulated board's are kept
    /// only when given.
    #[arg(long)]
    pub history: Option<PathBuf>,
}

/// Whether the command may replace its output file.
#[derive(Args, Clone, Copy, Debug)]
pub struct Overwrite {
    /// Replace the file this command writes (its -o, a certificate issued before, a new session's
    /// --stream-log) when it exists; without it, an existing file is refused and kept.
    #[arg(long)]
    pub overwrite: bool,
}
