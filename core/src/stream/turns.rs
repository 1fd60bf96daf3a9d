//! The gyro's scale and misalignment G from the turns a stream recorded between its still periods:
//! each turn's gyro samples, integrated through G, must carry the gravity one period measured onto
//! the next one's (`fit::gyro`, the fit accelcal's own boards use); and the gyro's range in counts,
//! which a resting gyro cannot tell, checked against the turns (G's scale is the ratio of the true
//! counts per deg/s to the assumed ones).

use shared::linalg::{mul_vec, norm, scale, sub};

use super::log::StreamLog;
use super::plausible::not_in_unit;
use super::segment::Segment;
use super::units::GyroUnit;
use crate::fit::gyro::{fit_gyro, GyroFit, GyroFitError, Turn};
use crate::fit::Fit;
use crate::limits::{GYRO_RANGE_TOLERANCE, MIN_TURN_RATE_HZ, UNIT_TURN_MIN_DEG, UNIT_TURN_RATIO};

/// The MPU-6050's gyro ranges in counts (register map 4.4, FS_SEL 0-3).
const COUNT_RANGES: [GyroUnit; 4] =
    [GyroUnit::Counts250, GyroUnit::Counts500, GyroUnit::Counts1000, GyroUnit::Counts2000];

/// The turns between successive still periods of `log`, gravity's direction at each through the
/// accelerometer's calibration `fit` (in the stream's unit); why there are none.
pub fn turns(log: &StreamLog, segments: &[Segment], fit: &Fit) -> Result<Vec<Turn>, String> {
    let gyro = log.gyro_dps().ok_or("the stream has no gyro")?;
    let hz = log.rate.map(|r| r.hz).ok_or("the stream's rate is unknown: the turns cannot be integrated")?;
    if hz < MIN_TURN_RATE_HZ {
        return Err(format!(
            "at {hz:.0} Hz a turn is too coarsely sampled to integrate (needs {MIN_TURN_RATE_HZ:.0} Hz)"
        ));
    }
    let per_g = log.accel_unit.per_g();
    let up = |s: &Segment| {
        let a = mul_vec(&fit.matrix, sub(scale(s.mean_g, per_g), fit.offset));
        scale(a, 1.0 / norm(a))
    };
    let turn = |(a, b): (&Segment, &Segment)| Turn {
        rates_dps: gyro[a.last + 1..b.first].to_vec(),
        interval_s: 1.0 / hz,
        bias_before_dps: a.gyro_mean_dps.unwrap_or_default(),
        bias_after_dps: b.gyro_mean_dps.unwrap_or_default(),
        up_before: up(a),
        up_after: up(b),
    };
    Ok(segments.iter().zip(segments.iter().skip(1)).map(turn).collect())
}

/// G fitted to the turns, and what they say of a gyro range that was assumed.
#[derive(Debug, Clone)]
pub struct TurnsFit {
    /// The fit, or why there is none.
    pub fit: Result<GyroFit, String>,
    /// The range check in words, for a gyro in counts.
    pub range: Option<String>,
}

/// Fits G to `turns` of a gyro read as `unit` (`assumed` when the stream did not say it).
pub fn fit(turns: Result<Vec<Turn>, String>, unit: GyroUnit, assumed: bool) -> TurnsFit {
    let turns = turns.and_then(|t| scale_doubt(&t, unit, assumed).map_or(Ok(t), Err));
    let fit = turns.and_then(|t| fit_gyro(&t).map_err(|e: GyroFitError| e.to_string()));
    let range = match &fit {
        Ok(g) => range_check(g, unit, assumed),
        Err(why) => (assumed && unit.is_counts()).then(|| unsettled(unit, why)),
    };
    TurnsFit { fit, range }
}

/// A gyro range assumed that the turns could not settle, asked for: its deg/s (the bias among
/// them) are the assumed range's, and another range scales them by 2, 4 or 8.
fn unsettled(unit: GyroUnit, why: &str) -> String {
    format!(
        "the gyro's range is not settled: the stream does not say it and its turns cannot ({why}); its deg/s are \
         those of the assumed {}: give --gyro-unit counts-250dps, counts-500dps, counts-1000dps or counts-2000dps \
         (the sketch's setFullScaleGyroRange), or --rate so that the turns settle it",
        unit.name()
    )
}

/// Why the gyro's values are not in `unit`, when the turns say so: integrated as `unit`, the gyro
/// turns the board many times further (or less far) than gravity's direction moved, before G is
/// fitted (or its failure blamed on the turns); the unit whose scale that implies.
fn scale_doubt(turns: &[Turn], unit: GyroUnit, assumed: bool) -> Option<String> {
    let mut ratios: Vec<f64> = turns.iter().filter_map(path_per_gravity_turn).collect();
    ratios.sort_by(f64::total_cmp);
    let ratio = *ratios.get(ratios.len() / 2)?;
    if (1.0 / UNIT_TURN_RATIO..=UNIT_TURN_RATIO).contains(&ratio) {
        return None;
    }
    let evidence = format!(
        "the gyro turns the board {ratio:.3} times as far as gravity's direction moved (the median of {} turns of \
         {UNIT_TURN_MIN_DEG:.0} degrees or more)",
        ratios.len()
    );
    Some(format!("the turns say {}", not_in_unit(unit, assumed, &evidence, GyroUnit::nearest(unit.per_dps() * ratio))))
}

/// How far the gyro turned the board along its path over `turn`, per degree gravity's direction
/// moved, for a turn that moved it [`UNIT_TURN_MIN_DEG`] or more.
///
/// NOTE: the path (the sum of each step's angle) rather than the net rotation: a gyro read 100 times
/// too fast turns the board round many times, which a net angle folds back below 180 degrees.
fn path_per_gravity_turn(turn: &Turn) -> Option<f64> {
    let gravity_deg =
        turn.up_before.iter().zip(&turn.up_after).map(|(a, b)| a * b).sum::<f64>().clamp(-1.0, 1.0).acos().to_degrees();
    let bias = [0, 1, 2].map(|k| (turn.bias_before_dps[k] + turn.bias_after_dps[k]) / 2.0);
    let path_deg: f64 = turn.rates_dps.iter().map(|r| norm(sub(*r, bias)) * turn.interval_s).sum();
    (gravity_deg >= UNIT_TURN_MIN_DEG).then(|| path_deg / gravity_deg)
}

/// The range whose counts per deg/s G's mean scale implies, in words, when the gyro is in counts.
fn range_check(fit: &GyroFit, unit: GyroUnit, assumed: bool) -> Option<String> {
    if !COUNT_RANGES.contains(&unit) {
        return None;
    }
    let g_scale = (0..3).map(|k| fit.matrix[k][k]).sum::<f64>() / 3.0;
    let implied = unit.per_dps() / g_scale;
    let near = COUNT_RANGES.iter().find(|r| (r.per_dps() / implied - 1.0).abs() <= GYRO_RANGE_TOLERANCE);
    let how = if assumed { "assumed" } else { "given" };
    Some(match near {
        Some(&range) if range == unit => {
            format!("the turns confirm the gyro's range: {} (G's mean scale {g_scale:.4})", unit.name())
        }
        Some(range) => format!(
            "the turns say the gyro prints {}, not the {how} {} (G's mean scale {g_scale:.3}): give --gyro-unit {}",
            range.name(),
            unit.name(),
            range.name()
        ),
        None => format!(
            "the turns fit no gyro range: G's mean scale {g_scale:.3} with {} {how} (is the gyro's unit something else? --gyro-unit)",
            unit.name()
        ),
    })
}
