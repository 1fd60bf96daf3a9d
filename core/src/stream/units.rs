//! The units a stream's values are in: some dialects fix them, otherwise the accelerometer's is
//! told by the size of gravity in the stream (most of a session rests, so the median |a| is 1 g in
//! whatever unit), and the gyro's follows the accelerometer's convention unless a flag says better.

use serde::Serialize;
use shared::{AccelRange, GyroRange, STANDARD_GRAVITY};

use super::conventions::Dialect;
use super::StreamError;
use crate::limits::{COUNTS_SPAN, READABLE_MARGIN, UNIT_TOLERANCE, WIDEST_RANGE_DPS, WIDEST_RANGE_G};

/// MotionCal's sketch prints acceleration as m/s^2 * 8192 / 9.8 (Adafruit's `calibration` example).
const MOTIONCAL_COUNTS_PER_MS2: f64 = 8192.0 / 9.8;
/// MotionCal's sketch prints the gyro as deg/s * 16.
const MOTIONCAL_COUNTS_PER_DPS: f64 = 16.0;

/// The unit of an accelerometer's values.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, strum::EnumString, strum::IntoStaticStr, strum::EnumIter, strum::EnumMessage,
)]
#[strum(serialize_all = "kebab-case")]
pub enum AccelUnit {
    #[strum(serialize = "g")]
    G,
    #[strum(serialize = "mg")]
    MilliG,
    #[strum(serialize = "m/s2")]
    MetersPerSecond2,
    /// Counts of the +-2 g range, 16384 a g (MPU-6050 Product Specification 6.2).
    #[strum(serialize = "counts-2g")]
    Counts2g,
    #[strum(serialize = "counts-4g")]
    Counts4g,
    #[strum(serialize = "counts-8g")]
    Counts8g,
    #[strum(serialize = "counts-16g")]
    Counts16g,
    /// MotionCal's m/s^2 * 8192 / 9.8.
    #[strum(serialize = "motioncal-counts")]
    MotionCal,
}

/// The unit of a gyro's values.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, strum::EnumString, strum::IntoStaticStr, strum::EnumIter, strum::EnumMessage,
)]
#[strum(serialize_all = "kebab-case")]
pub enum GyroUnit {
    #[strum(serialize = "deg/s")]
    DegPerS,
    #[strum(serialize = "rad/s")]
    RadPerS,
    /// Counts of the +-250 deg/s range, 131 a deg/s (Product Specification 6.1).
    #[strum(serialize = "counts-250dps")]
    Counts250,
    #[strum(serialize = "counts-500dps")]
    Counts500,
    #[strum(serialize = "counts-1000dps")]
    Counts1000,
    #[strum(serialize = "counts-2000dps")]
    Counts2000,
    /// MotionCal's deg/s * 16.
    #[strum(serialize = "motioncal-counts")]
    MotionCal,
}

/// A unit a line names in words after its values.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UnitWord {
    /// The accelerometer's: `m/s^2`, `g`, `mg`.
    Accel(AccelUnit),
    /// The gyro's: `rad/s`, `deg/s`, `°/s`, `degrees/s`.
    Gyro(GyroUnit),
}

/// The unit `word` names, when it is one a sketch prints after a value (Adafruit's `m/s^2` and
/// `rad/s`, ESPHome's `m/s²` and `°/s`, kriswiner's `mg` and `degrees/s`).
pub(super) fn unit_word(word: &str) -> Option<UnitWord> {
    let word = word.trim_end_matches(['.', ',']).to_lowercase();
    Some(match word.as_str() {
        "m/s^2" | "m/s2" | "m/s²" | "m/s/s" | "ms^-2" => UnitWord::Accel(AccelUnit::MetersPerSecond2),
        "g" => UnitWord::Accel(AccelUnit::G),
        "mg" => UnitWord::Accel(AccelUnit::MilliG),
        "rad/s" | "rad/sec" | "rads/s" => UnitWord::Gyro(GyroUnit::RadPerS),
        "deg/s" | "°/s" | "º/s" | "dps" | "degrees/s" | "degrees/sec" | "deg/sec" => {
            UnitWord::Gyro(GyroUnit::DegPerS)
        }
        _ => return None,
    })
}

const ACCEL_UNITS: [AccelUnit; 7] = [
    AccelUnit::G,
    AccelUnit::MilliG,
    AccelUnit::MetersPerSecond2,
    AccelUnit::Counts2g,
    AccelUnit::Counts4g,
    AccelUnit::Counts8g,
    AccelUnit::Counts16g,
];

/// The units a gyro's values may be in, by their scale (MotionCal's counts come with its dialect).
const GYRO_UNITS: [GyroUnit; 6] = [
    GyroUnit::DegPerS,
    GyroUnit::RadPerS,
    GyroUnit::Counts250,
    GyroUnit::Counts500,
    GyroUnit::Counts1000,
    GyroUnit::Counts2000,
];

impl AccelUnit {
    /// How many of the unit make a g.
    pub fn per_g(self) -> f64 {
        match self {
            AccelUnit::G => 1.0,
            AccelUnit::MilliG => 1000.0,
            AccelUnit::MetersPerSecond2 => STANDARD_GRAVITY,
            AccelUnit::Counts2g => f64::from(AccelRange::G2.lsb_per_g()),
            AccelUnit::Counts4g => mutant!("stream-counts-4g-as-2g", f64::from(AccelRange::G4.lsb_per_g()), 16384.0),
            AccelUnit::Counts8g => f64::from(AccelRange::G8.lsb_per_g()),
            AccelUnit::Counts16g => f64::from(AccelRange::G16.lsb_per_g()),
            AccelUnit::MotionCal => MOTIONCAL_COUNTS_PER_MS2 * STANDARD_GRAVITY,
        }
    }

    /// The range a stream's counts name; +-2 g (the chip's power-on range) for values in g or m/s^2,
    /// whose range the stream does not say.
    pub fn range(self) -> AccelRange {
        match self {
            AccelUnit::Counts4g => AccelRange::G4,
            AccelUnit::Counts8g => AccelRange::G8,
            AccelUnit::Counts16g => AccelRange::G16,
            _ => AccelRange::G2,
        }
    }

    /// Whether the unit is a range's raw counts.
    pub fn is_counts(self) -> bool {
        matches!(self, AccelUnit::Counts2g | AccelUnit::Counts4g | AccelUnit::Counts8g | AccelUnit::Counts16g)
    }

    /// The largest size a value in this unit can have and be a reading: the counts' 16-bit span,
    /// else the widest range, each with [`READABLE_MARGIN`].
    pub fn readable_max(self) -> f64 {
        READABLE_MARGIN * if self.is_counts() { COUNTS_SPAN } else { WIDEST_RANGE_G * self.per_g() }
    }

    /// The name `--input-unit` takes and `--json` prints.
    pub fn name(self) -> &'static str {
        match self {
            AccelUnit::G => "g",
            AccelUnit::MilliG => "mg",
            AccelUnit::MetersPerSecond2 => "m/s2",
            AccelUnit::Counts2g => "counts-2g",
            AccelUnit::Counts4g => "counts-4g",
            AccelUnit::Counts8g => "counts-8g",
            AccelUnit::Counts16g => "counts-16g",
            AccelUnit::MotionCal => "motioncal-counts",
        }
    }

    /// The unit the dialect fixes, or the one whose g the median |a| is near.
    pub fn infer(dialect: Dialect, median_norm: f64) -> Result<AccelUnit, StreamError> {
        match dialect {
            Dialect::AdafruitPlotter | Dialect::Kalibr => return Ok(AccelUnit::MetersPerSecond2),
            Dialect::Motioncal => return Ok(AccelUnit::MotionCal),
            _ => {}
        }
        ACCEL_UNITS.iter().find(|unit| unit.fits(median_norm)).copied().ok_or(StreamError::UnclearUnit { median_norm })
    }

    /// Whether gravity's size `median_norm` (the median |a|, in this unit) is 1 g in this unit.
    pub(super) fn fits(self, median_norm: f64) -> bool {
        (median_norm / self.per_g() - 1.0).abs() <= UNIT_TOLERANCE
    }

    /// This unit, given by `--input-unit`, unless gravity's size is not 1 g in it and is in another
    /// (counts given as g: 16384 "g" at rest): that one named, before any period or position is judged.
    pub fn given(self, dialect: Dialect, median_norm: f64) -> Result<AccelUnit, StreamError> {
        match AccelUnit::infer(dialect, median_norm) {
            Ok(likely) if likely != self && !self.fits(median_norm) => {
                Err(StreamError::OtherAccelUnit { given: self, likely, median_norm })
            }
            _ => Ok(self),
        }
    }
}

impl GyroUnit {
    /// How many of the unit make a deg/s.
    pub fn per_dps(self) -> f64 {
        match self {
            GyroUnit::DegPerS => 1.0,
            GyroUnit::RadPerS => 1f64.to_radians(),
            GyroUnit::Counts250 => GyroRange::Dps250.lsb_per_dps(),
            GyroUnit::Counts500 => GyroRange::Dps500.lsb_per_dps(),
            GyroUnit::Counts1000 => mutant!("stream-gyro-1000-rounded", GyroRange::Dps1000.lsb_per_dps(), 33.0),
            GyroUnit::Counts2000 => GyroRange::Dps2000.lsb_per_dps(),
            GyroUnit::MotionCal => MOTIONCAL_COUNTS_PER_DPS,
        }
    }

    /// The unit whose scale is within 1.5 times `per_dps` (units per deg/s), when one is: the
    /// units' scales are 2 times apart or more.
    pub fn nearest(per_dps: f64) -> Option<GyroUnit> {
        let distance = |u: &GyroUnit| (u.per_dps() / per_dps).ln().abs();
        GYRO_UNITS.into_iter().filter(|u| distance(u) <= 1.5f64.ln()).min_by(|a, b| distance(a).total_cmp(&distance(b)))
    }

    /// Whether the unit is a range's raw counts (what int16 readings are).
    pub fn is_counts(self) -> bool {
        matches!(self, GyroUnit::Counts250 | GyroUnit::Counts500 | GyroUnit::Counts1000 | GyroUnit::Counts2000)
    }

    /// Raw counts per deg/s when the unit is a range's counts, else none.
    pub fn counts_per_dps(self) -> Option<f64> {
        self.is_counts().then(|| self.per_dps())
    }

    /// The largest size a value in this unit can have and be a reading, as [`AccelUnit::readable_max`].
    pub fn readable_max(self) -> f64 {
        READABLE_MARGIN * if self.is_counts() { COUNTS_SPAN } else { WIDEST_RANGE_DPS * self.per_dps() }
    }

    /// The name `--gyro-unit` takes and `--json` prints.
    pub fn name(self) -> &'static str {
        match self {
            GyroUnit::DegPerS => "deg/s",
            GyroUnit::RadPerS => "rad/s",
            GyroUnit::Counts250 => "counts-250dps",
            GyroUnit::Counts500 => "counts-500dps",
            GyroUnit::Counts1000 => "counts-1000dps",
            GyroUnit::Counts2000 => "counts-2000dps",
            GyroUnit::MotionCal => "motioncal-counts",
        }
    }

    /// The unit the dialect fixes (true), else the one that goes with the accelerometer's (false:
    /// an assumption the report states, with the flag that settles it).
    pub fn infer(dialect: Dialect, accel: AccelUnit) -> (GyroUnit, bool) {
        match (dialect, accel) {
            (Dialect::AdafruitPlotter | Dialect::Kalibr, _) => (GyroUnit::RadPerS, true),
            (Dialect::Motioncal, _) => (GyroUnit::MotionCal, true),
            (_, AccelUnit::G | AccelUnit::MilliG) => (GyroUnit::DegPerS, false),
            (_, AccelUnit::MetersPerSecond2) => (GyroUnit::RadPerS, false),
            // NOTE: +-250 deg/s is the MPU-6050's range at power-on (register map 4.4, FS_SEL = 0),
            // which i2cdevlib's and most loggers' examples keep.
            _ => (GyroUnit::Counts250, false),
        }
    }
}

impl Serialize for AccelUnit {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.name())
    }
}

impl Serialize for GyroUnit {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gravitys_size_names_the_unit_and_a_size_that_fits_none_names_the_flag() {
        let unit = |norm| AccelUnit::infer(Dialect::Csv, norm).map_err(|e| e.to_string());
        assert_eq!(unit(16_690.0), Ok(AccelUnit::Counts2g));
        assert_eq!(unit(8_100.0), Ok(AccelUnit::Counts4g));
        assert_eq!(unit(2_050.0), Ok(AccelUnit::Counts16g));
        assert_eq!(unit(0.93), Ok(AccelUnit::G));
        assert_eq!(unit(9.6), Ok(AccelUnit::MetersPerSecond2));
        assert_eq!(unit(1010.0), Ok(AccelUnit::MilliG));
        assert!(unit(3.0).unwrap_err().contains("--input-unit"), "{:?}", unit(3.0));
        assert_eq!(AccelUnit::infer(Dialect::AdafruitPlotter, 1.0).unwrap(), AccelUnit::MetersPerSecond2);
        assert_eq!(AccelUnit::Counts2g.name(), "counts-2g");
        assert_eq!(GyroUnit::RadPerS.name(), "rad/s");
    }

    // NOTE: the MPU-6000/6050 Product Specification, 6.1: 131, 65.5, 32.8 and 16.4 LSB/(deg/s) at
    // FS_SEL 0-3 (+-250 to +-2000 deg/s); 16384 to 2048 LSB/g at AFS_SEL 0-3 (6.2).
    #[test]
    fn a_stream_s_counts_are_read_at_the_datasheet_s_sensitivity_of_their_range() {
        let log = |header: &str, row: &str, gyro_unit| {
            let text: String = (0..50).map(|i| format!("{}{row}\n", i * 10)).collect();
            let options = super::super::StreamOptions { gyro_unit, ..Default::default() };
            super::super::StreamLog::parse(&format!("{header}\n{text}"), &options).unwrap()
        };
        let counts = log("millis,ax,ay,az,gx,gy,gz", ",0,0,8192,328,-164,3280", Some(GyroUnit::Counts1000));
        assert_eq!(counts.accel_unit, AccelUnit::Counts4g);
        let accel_g = counts.samples[0].accel.map(|v| v / counts.accel_unit.per_g());
        assert_eq!(accel_g, [0.0, 0.0, 1.0]);
        let gyro_dps = counts.gyro_dps().unwrap()[0];
        for (got, wanted) in gyro_dps.iter().zip([10.0, -5.0, 100.0]) {
            assert!((got - wanted).abs() < 1e-9, "{gyro_dps:?}");
        }
    }
}
