//! A self-test's result as `selftest --json` prints it and as a person reads it.

use serde::Serialize;
use shared::part::Family;
use shared::protocol::SensorIdentity;
use shared::selftest::{self, AxisVerdict, StoredSelfTest, ACCELCAL_BAND_PERCENT};

use super::HistoryEntry;
use super::SelfTest;
use crate::part::{describe, family_name, part_name};
use crate::shown::utc_minutes;

/// What `accelcal selftest --json` prints (and the history keeps).
#[derive(Debug, Clone, Serialize)]
pub struct SelfTestJson {
    /// The part's name, or "unknown".
    pub part: &'static str,
    /// The WHO_AM_I value.
    pub who_am_i: u8,
    /// The register family the procedure ran as.
    pub family: &'static str,
    /// Every axis within accelcal's band (+-14 % of its factory trim on every family).
    pub passed: bool,
    /// Every axis within its family's own datasheet band.
    pub datasheet_passed: bool,
    /// How many attempts it took (more than 1: the board moved and the test was repeated).
    pub attempts: u8,
    /// Accelerometer x, y, z then gyro x, y, z.
    pub axes: Vec<AxisJson>,
}

/// One axis: its verdict (`axis`, `response`, `factory_trim`, `deviation_percent`, `passed`,
/// `datasheet_passed`, `code`; accelerometer values in g, gyro values in deg/s) and the raw means.
#[derive(Debug, Clone, Serialize)]
pub struct AxisJson {
    #[serde(flatten)]
    pub verdict: AxisVerdict,
    /// Mean output with self-test off and on, in LSB at the self-test ranges.
    pub off_lsb: f32,
    pub on_lsb: f32,
}

impl SelfTestJson {
    /// The JSON form of a self-test.
    pub fn of(test: &SelfTest) -> Self {
        let raw = &test.raw;
        let axes = test.verdicts.iter().enumerate();
        SelfTestJson {
            part: part_name(&test.identity),
            who_am_i: test.identity.who_am_i,
            family: family_name(test.identity.family),
            passed: test.passed(),
            datasheet_passed: shared::selftest::datasheet_passed(&test.verdicts),
            attempts: raw.attempts,
            axes: axes
                .map(|(i, &verdict)| AxisJson { verdict, off_lsb: raw.off_lsb[i], on_lsb: raw.on_lsb[i] })
                .collect(),
        }
    }
}

/// The family's own band, in words.
fn datasheet_band(family: Family) -> &'static str {
    match family {
        Family::Mpu6050 => "+-14 %, PS-MPU-6000A",
        Family::Mpu6500 => "accel +-50 %, gyro from -50 %, AN-MPU-6500A",
    }
}

/// A history entry keeps a self-test as its JSON report, made here.
impl HistoryEntry {
    /// The entry of a self-test run at `unix_time_s` (seconds since 1970, UTC).
    pub fn at(result: &SelfTestJson, unix_time_s: f64) -> Self {
        let date_utc = utc_minutes(unix_time_s);
        HistoryEntry { date_utc, result: serde_json::to_value(result).unwrap_or_default() }
    }

    /// The entry of the self-test a board keeps in flash (`record`), run on the sensor `identity`;
    /// `None` when the record is not one.
    pub fn of_board(identity: SensorIdentity, record: &[u8]) -> Option<Self> {
        let stored = StoredSelfTest::from_record(record)?;
        let test = SelfTest { identity, raw: stored.raw, verdicts: selftest::evaluate(&stored.raw) };
        let date_utc = utc_minutes(f64::from(stored.unix_time_s));
        Some(HistoryEntry { date_utc, result: serde_json::to_value(SelfTestJson::of(&test)).unwrap_or_default() })
    }
}

/// The self-test for a person: the sensor, a line per axis (beside the previous result's deviation
/// when there is one), and the verdict.
pub fn text(test: &SelfTest, previous: Option<&HistoryEntry>) -> String {
    let range = test.identity.family.self_test_range().full_scale_g();
    let attempts = test.raw.attempts;
    let mut out = format!(
        "sensor: {}\nself-test at +-{range} g and +-250 deg/s, {attempts} attempt{}\n",
        describe(&test.identity),
        if attempts == mutant!("selftest-attempts-plural", 1, 0) { "" } else { "s (the board moved; repeated)" }
    );
    out += &format!(
        "{:<8} {:>12} {:>13} {:>9} {:>5}  {:<9} {:<9}{}\n",
        "axis",
        "response",
        "factory trim",
        "deviation",
        "code",
        "accelcal",
        "datasheet",
        previous.map_or(String::new(), |p| format!("  previous ({})", p.date_utc))
    );
    for (i, v) in test.verdicts.iter().enumerate() {
        out += &axis_line(v, previous.map(|p| p.deviation_percent(i)));
    }
    out + &verdict_lines(test)
}

/// An axis's line; `previous` is the previous self-test's deviation of the axis, if there was one.
fn axis_line(v: &AxisVerdict, previous: Option<Option<f32>>) -> String {
    let unit = if v.axis.starts_with("accel") { "g" } else { "dps" };
    let trim = v.factory_trim.map_or("none".to_owned(), |t| format!("{t:.3} {unit}"));
    let previous = previous.map_or(String::new(), |p| format!("  {}", percent(p)));
    format!(
        "{:<8} {:>12} {trim:>13} {:>9} {:>5}  {:<9} {:<9}{previous}\n",
        v.axis,
        format!("{:.3} {unit}", v.response),
        percent(v.deviation_percent),
        v.code,
        pass(v.passed),
        pass(v.datasheet_passed)
    )
}

fn verdict_lines(test: &SelfTest) -> String {
    let datasheet = shared::selftest::datasheet_passed(&test.verdicts);
    let family = test.identity.family;
    let own = format!("by the {} family's own band ({})", family_name(family), datasheet_band(family));
    if test.passed() {
        return format!("PASSED: every axis within +-{ACCELCAL_BAND_PERCENT} % of its factory trim\n");
    }
    let failed: Vec<&str> = test.verdicts.iter().filter(|v| !v.passed).map(|v| v.axis).collect();
    format!(
        "FAILED: {} outside +-{ACCELCAL_BAND_PERCENT} % of the factory trim (accelcal's band on every family); {own} it {}\n",
        failed.join(", "),
        if datasheet { "passes" } else { "fails too" }
    )
}

fn percent(value: Option<f32>) -> String {
    value.map_or("-".to_owned(), |p| format!("{p:+.1} %"))
}

fn pass(passed: bool) -> &'static str {
    if passed {
        "pass"
    } else {
        "FAIL"
    }
}
