//! `accelcal export`: the calibration in the formats other people's code already reads. Each target
//! writes the calibration in its own units and convention, states in its own comment syntax what it
//! applies and what it cannot carry ([`statement`]), and what that costs on this unit ([`loss`]).

mod adafruit;
mod code;
mod fixed;
mod flight;
mod fusion;
mod i2cdevlib;
mod kalibr;
pub mod loss;
mod matlab;
mod multiwii;
pub mod source;
pub mod statement;

pub use loss::{Carried, Loss};
pub use source::{Noise, Readings, Source};

use crate::calibration::CalibrationRecordError;
use crate::fit::FitError;

/// Standard gravity, m/s^2 per g: the g every m/s^2 value of an export is converted with
/// (CGPM 1901; the value ArduPilot's GRAVITY_MSS, PX4's CONSTANTS_ONE_G and Adafruit's
/// SENSORS_GRAVITY_STANDARD use).
pub const STANDARD_GRAVITY: f64 = 9.80665;
/// Gyro sensitivity at the +-1000 deg/s the firmware sets, LSB per deg/s (Product Specification 6.1).
pub const GYRO_LSB_PER_DPS: f64 = 32.8;

/// The formats `--to` takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Target {
    /// C header, float: M, o, G, b and apply functions (raw counts to g, m/s^2, deg/s); carries everything.
    C,
    /// C header, Q14 int16 matrix and int16 offsets in counts, int32 arithmetic (8-bit parts); carries everything to its stated step.
    CFixed,
    /// Rust module (no_std): const M, o, G, b and apply functions; carries everything.
    Rust,
    /// xio Fusion: FusionMatrix/FusionVector values for FusionCalibrationInertial; carries everything.
    Fusion,
    /// Adafruit_Sensor_Calibration sensor_calib.json: accel and gyro offsets only (SI units).
    AdafruitJson,
    /// Adafruit_Sensor_Calibration's 68-byte EEPROM image (MotionCal's layout, CRC-16): offsets only; needs -o.
    AdafruitEeprom,
    /// ArduPilot .param: INS_ACCOFFS/INS_ACCSCAL (offsets, diagonal scale), INS_GYROFFS, TCAL temperature model.
    Ardupilot,
    /// PX4 .params (QGroundControl's tab-separated form): CAL_ACC0 offsets and diagonal scale, CAL_GYRO0, TC_A0/TC_G0.
    Px4,
    /// Betaflight CLI: set acc_calibration (offsets only, raw counts).
    Betaflight,
    /// INAV CLI: acczero (offsets) and accgain (diagonal scale).
    Inav,
    /// MATLAB/Octave script: A and b in magcal's C = (D - b) * A, row vectors; carries everything.
    Matlab,
    /// i2cdevlib MPU6050 offset-register calls (setXAccelOffset, setXGyroOffset): offsets only.
    I2cdevlib,
    /// Kalibr imu.yaml with the noise terms of --noise NOISE.json (the calibration is stated, not carried).
    Kalibr,
}

/// An exported file.
#[derive(Debug, Clone, PartialEq)]
pub struct Export {
    /// The file's bytes.
    pub bytes: Vec<u8>,
    /// Whether the file is binary (no comment syntax: the statement goes to the terminal instead).
    pub binary: bool,
    /// What the file states, as plain lines (for a binary file, shown beside it).
    pub statement: Vec<String>,
    /// What the target loses on this unit.
    pub loss: Loss,
}

/// Why an export could not be made.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    #[error("not JSON: {reason}; give the output of calibrate --json, fit --json, download, or a session file")]
    NotJson { reason: String },
    #[error(transparent)]
    Record(#[from] CalibrationRecordError),
    #[error("the session cannot be fitted: {0}; capture the positions it lacks (calibrate --resume SESSION)")]
    Fit(FitError),
    #[error("not a noise report: {reason}")]
    NoiseFile { reason: String },
    #[error("kalibr's imu.yaml is noise terms: give --noise NOISE.json (from `accelcal noise RECORDING --json`)")]
    NeedsNoise,
    #[error("the noise report was recorded on board {recorded}, the calibration is board {calibrated}'s: every board's noise differs; record this board (`accelcal record --port P` then `accelcal noise RECORDING --json`)")]
    NoiseOfAnotherBoard { calibrated: String, recorded: String },
    #[error("{target} is a binary file: give -o FILE")]
    BinaryNeedsFile { target: String },
    #[error("the fixed-point form would overflow int32 ({reason}); use --to c")]
    FixedPointOverflow { reason: String },
}

/// The export of `source` to `target`.
pub fn export(source: &Source, target: Target) -> Result<Export, ExportError> {
    match target {
        Target::C => Ok(code::c(source)),
        Target::CFixed => fixed::c_fixed(source),
        Target::Rust => Ok(code::rust(source)),
        Target::Fusion => Ok(fusion::fusion(source)),
        Target::AdafruitJson => Ok(adafruit::json(source)),
        Target::AdafruitEeprom => Ok(adafruit::eeprom(source)),
        Target::Ardupilot => Ok(flight::ardupilot(source)),
        Target::Px4 => Ok(flight::px4(source)),
        Target::Betaflight => Ok(multiwii::betaflight(source)),
        Target::Inav => Ok(multiwii::inav(source)),
        Target::Matlab => Ok(matlab::matlab(source)),
        Target::I2cdevlib => Ok(i2cdevlib::i2cdevlib(source)),
        Target::Kalibr => kalibr::kalibr(source),
    }
}

/// A comment syntax: an opening line, a prefix for each line, a closing line.
struct Comment {
    open: &'static str,
    line: &'static str,
    close: &'static str,
}

/// `// ...` (C++, Rust).
const SLASHES: Comment = Comment { open: "", line: "// ", close: "" };
/// `# ...` (parameter files, YAML).
const HASH: Comment = Comment { open: "", line: "# ", close: "" };
/// `/* ... */` (C).
const C_BLOCK: Comment = Comment { open: "/*\n", line: " * ", close: " */\n" };

/// A text export: the statement in the file's comment syntax, then the body.
fn text(statement: Vec<String>, comment: &Comment, body: &str, loss: Loss) -> Export {
    let mut out = comment.open.to_owned();
    for line in &statement {
        out.push_str(format!("{}{line}", comment.line).trim_end());
        out.push('\n');
    }
    out.push_str(comment.close);
    out.push_str(body);
    Export { bytes: out.into_bytes(), binary: false, statement, loss }
}

/// An f32 value as the shortest decimal that reads back to the same f32 (valid C, Rust, MATLAB).
fn float(value: f64) -> String {
    format!("{:e}", value as f32)
}

/// A session's calibration as the exports take it, with a gyro bias of 1, -0.5 and 0.25 deg/s (so
/// that each axis' sign and rounding show).
#[cfg(test)]
pub(crate) fn example_source() -> Source {
    let session = crate::certificate::tests::session(1, 1.4, 2.8e-3);
    let mut source = Source::from_session(&session, "s.json").expect("the example session fits");
    source.calibration.gyro.bias_dps = [1.0, -0.5, 0.25];
    source
}

/// The three numbers of `name = {x, y, z};` in a C export (`1.5e0f` as 1.5).
#[cfg(test)]
pub(crate) fn c_vector_of(text: &str, name: &str) -> Option<[f64; 3]> {
    let line = text.lines().find(|l| l.contains(&format!(" {name} = ")))?;
    let inside = line.split(['{', '}']).nth(1)?;
    let numbers: Vec<f64> = inside.split(',').filter_map(|v| v.trim().trim_end_matches('f').parse().ok()).collect();
    numbers.try_into().ok()
}
