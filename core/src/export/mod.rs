//! `accelcal export`: the calibration in the formats other people's code already reads. Each target
//! writes the calibration in its own units and convention, states in its own comment syntax what it
//! applies and what it cannot carry ([`statement`]), and what that costs on this unit ([`loss`]).

mod adafruit;
mod code;
mod esphome;
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
mod written;

pub use loss::{Carried, Loss};
pub use source::{Noise, Readings, Source};
use written::{float, text, Comment, C_BLOCK, HASH, SLASHES};
pub use written::{Export, ExportError};

/// The formats `--to` takes.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, strum::EnumString, strum::IntoStaticStr, strum::EnumIter, strum::EnumMessage,
)]
#[strum(serialize_all = "kebab-case")]
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
    /// ESPHome sensor: fragment for the mpu6050 platform: per-axis filters (offsets, scale) and template sensors carrying everything.
    Esphome,
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
        Target::Esphome => Ok(esphome::esphome(source)),
    }
}

/// A session's calibration as the exports take it, with a gyro bias of 1, -0.5 and 0.25 deg/s (so
/// that each axis' sign and rounding show).
#[cfg(test)]
pub(crate) fn example_source() -> Source {
    let session = crate::sim::sessions::adaptive(1, 1.4, 2.8e-3);
    let mut source = Source::from_session(&session, "s.json").expect("the example session fits");
    source.calibration.gyro.bias_dps = [1.0, -0.5, 0.25];
    source
}

/// The three numbers of `name = {x, y, z};` (or `{{x, y, z}}`) in a C export (`1.5e0f` as 1.5).
#[cfg(test)]
pub(crate) fn c_vector_of(text: &str, name: &str) -> Option<[f64; 3]> {
    let line = text.lines().find(|l| l.contains(&format!(" {name} = ")))?;
    let inside = line.split(['{', '}']).find(|part| part.contains(','))?;
    let numbers: Vec<f64> = inside.split(',').filter_map(|v| v.trim().trim_end_matches('f').parse().ok()).collect();
    numbers.try_into().ok()
}
