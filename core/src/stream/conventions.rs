//! The printing conventions accelcal reads, by name: below the detection that finds a stream's
//! ([`super::dialect`]), the columns and the units each implies.

use serde::Serialize;

/// The printing conventions accelcal reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Dialect {
    /// i2cdevlib's MPU6050_raw example: `a/g:` and six counts, tab-separated.
    I2cdevlib,
    /// Adafruit's calibration sketch for MotionCal: `Raw:` and nine counts, `Uni:`/`Cal1:`/`Cal2:` between.
    Motioncal,
    /// Adafruit_MPU6050's plotter example: `AccelX:0.61,...,GyroZ:0.00` in m/s^2 and rad/s.
    AdafruitPlotter,
    /// The Arduino Serial Plotter's `label:value` pairs, any labels.
    SerialPlotter,
    /// Comma-separated values, with or without a header line.
    Csv,
    /// Numbers separated by spaces or tabs.
    Whitespace,
    /// A MicroPython tuple printed per line: `(0.06, -0.05, 0.93)`.
    Micropython,
    /// Kalibr's IMU CSV: `timestamp,omega_x,omega_y,omega_z,alpha_x,alpha_y,alpha_z` (ns, rad/s, m/s^2).
    Kalibr,
    /// Semicolon-separated values with decimal commas (a European-locale CSV): `0,0123;-0,0456;...`.
    SemicolonCsv,
    /// JSON objects or Python dictionaries, one a line: `{"ax":0.12,...}`, `{'AcX': 1234, ...}`.
    Json,
    /// Bracketed arrays, one a line: `[0.12, -0.34, 9.81, ...]`.
    Array,
    /// Values among words, one sample a line: `AcX = 1234 | AcY = -56 | ...`.
    Labelled,
    /// One sample printed over several lines (Adafruit's `basic_readings`, ESPHome's log).
    MultiLine,
}

impl Dialect {
    /// The name `--json` prints and the report shows.
    pub fn name(self) -> &'static str {
        match self {
            Dialect::I2cdevlib => "i2cdevlib",
            Dialect::Motioncal => "motioncal",
            Dialect::AdafruitPlotter => "adafruit-plotter",
            Dialect::SerialPlotter => "serial-plotter",
            Dialect::Csv => "csv",
            Dialect::Whitespace => "whitespace",
            Dialect::Micropython => "micropython",
            Dialect::Kalibr => "kalibr",
            Dialect::SemicolonCsv => "semicolon-csv",
            Dialect::Json => "json",
            Dialect::Array => "array",
            Dialect::Labelled => "labelled",
            Dialect::MultiLine => "multi-line",
        }
    }
}
