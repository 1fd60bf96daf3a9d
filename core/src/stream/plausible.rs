//! Whether a stream's gyro values are in the unit they are read in, judged before a still period or
//! a turn is blamed: a resting board's gyro (where the accelerometer rests) reads its bias, within
//! tens of deg/s, and scatters by a fraction of one; read in the wrong unit it does neither.

use shared::linalg::{norm, sub};

use super::log::StreamLog;
use super::segment::{median3, segment, Segment, Stillness};
use super::units::GyroUnit;
use crate::limits::{GYRO_REST_MAX_DPS, GYRO_REST_SCATTER_MAX_DPS};

/// What a resting board's gyro reads in one unit, in deg/s.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Rest {
    /// The largest axis of its median (the bias).
    bias_dps: f64,
    /// The median distance of a resting sample from the bias.
    scatter_dps: f64,
}

impl Rest {
    fn plausible(self) -> bool {
        self.bias_dps <= GYRO_REST_MAX_DPS && self.scatter_dps <= GYRO_REST_SCATTER_MAX_DPS
    }
}

/// The gyro's samples inside the accelerometer's still periods, read as `unit`.
fn at_rest(raw: &[[f64; 3]], still: &[Segment], unit: GyroUnit) -> Option<Rest> {
    let resting: Vec<[f64; 3]> =
        still.iter().flat_map(|s| &raw[s.first..=s.last]).map(|g| g.map(|v| v / unit.per_dps())).collect();
    if resting.is_empty() {
        return None;
    }
    let bias = median3(&resting);
    let mut distances: Vec<f64> = resting.iter().map(|g| norm(sub(*g, bias))).collect();
    distances.sort_by(f64::total_cmp);
    Some(Rest {
        bias_dps: bias.map(f64::abs).into_iter().fold(0.0, f64::max),
        scatter_dps: distances[distances.len() / 2],
    })
}

/// Why the gyro's values are not in the unit they are read in, when a resting board's gyro reads
/// what no resting gyro does in it, with the unit they fit (deg/s, else the power-on range's counts).
pub fn gyro_doubt(log: &StreamLog) -> Option<String> {
    let (unit, assumed) = log.gyro_unit?;
    let raw: Vec<[f64; 3]> = log.samples.iter().map(|s| s.gyro).collect::<Option<_>>()?;
    let still = segment(&log.accel_g(), None, &Stillness::for_rate(log.rate.map(|r| r.hz)));
    let rest = at_rest(&raw, &still, unit).filter(|rest| !rest.plausible())?;
    let fits = |other: &GyroUnit| *other != unit && at_rest(&raw, &still, *other).is_some_and(Rest::plausible);
    let likely = [GyroUnit::DegPerS, GyroUnit::Counts250].into_iter().find(fits);
    let evidence = format!(
        "the gyro of the resting board ({} samples where the accelerometer rests) reads {:.1} deg/s and scatters by \
         {:.1} deg/s, where a resting gyro reads within {GYRO_REST_MAX_DPS:.0} deg/s and scatters by a fraction of one",
        still.iter().map(|s| s.samples).sum::<usize>(),
        rest.bias_dps,
        rest.scatter_dps,
    );
    Some(not_in_unit(unit, assumed, &evidence, likely))
}

/// The gyro's values named as not in `unit` (`assumed`, or given), for `evidence`, with the way out.
pub fn not_in_unit(unit: GyroUnit, assumed: bool, evidence: &str, likely: Option<GyroUnit>) -> String {
    let how = if assumed { "assumed" } else { "given" };
    let way_out = match likely {
        Some(likely) => format!("they fit {}: give --gyro-unit {}", likely.name(), likely.name()),
        None => "give --gyro-unit as the sketch prints them".to_owned(),
    };
    format!("the gyro's values are not in the {how} unit {}: read so, {evidence}; {way_out}", unit.name())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fit::{FitOptions, Model, ModelChoice};
    use crate::report::stream::{StreamFitError, StreamReport};
    use crate::sim::person::PersonSession;
    use crate::sim::sketch::Sketch;
    use crate::stream::{AccelUnit, StreamOptions};

    /// A simulated person's session as `sketch` prints it, read with `options`.
    fn read(sketch: Sketch, options: StreamOptions) -> Result<StreamLog, String> {
        let session = PersonSession::new(5, sketch.reading());
        let text: String = sketch.lines(&session).into_iter().map(|l| l.text).collect();
        StreamLog::parse(&text, &options).map_err(|e| e.to_string())
    }

    fn gyro_in(unit: GyroUnit) -> StreamOptions {
        StreamOptions { gyro_unit: Some(unit), ..StreamOptions::default() }
    }

    fn report(log: &StreamLog) -> Result<StreamReport, StreamFitError> {
        StreamReport::new(log, ModelChoice::Only(Model::Ortho9), &FitOptions::default())
    }

    #[test]
    fn counts_given_as_g_or_mg_are_named_as_counts_with_the_flag_before_any_position_is_judged() {
        let accel_in = |unit| StreamOptions { accel_unit: Some(unit), ..StreamOptions::default() };
        for unit in [AccelUnit::G, AccelUnit::MilliG] {
            let error = read(Sketch::Csv, accel_in(unit)).unwrap_err();
            assert!(error.contains("they are counts-2g (16384 a g), not "), "{error}");
            assert!(error.contains("give --input-unit counts-2g"), "{error}");
            assert!(!error.contains("positions") && !error.contains("orientations"), "{error}");
        }
        let error = read(Sketch::Micropython, accel_in(AccelUnit::Counts2g)).unwrap_err();
        assert!(error.contains("that is 0.000 g") && error.contains("give --input-unit g,"), "{error}");
        // The unit given that gravity's size fits stands, as does one a margin off (counts of a chip 20 % hot).
        assert!(read(Sketch::Csv, accel_in(AccelUnit::Counts2g)).is_ok());
    }

    #[test]
    fn a_gyro_unit_that_puts_every_sample_beyond_reach_is_named_not_the_sample_count() {
        let error = read(Sketch::Csv, gyro_in(GyroUnit::RadPerS)).unwrap_err();
        assert!(error.contains("beyond what the sensor can read in rad/s"), "{error}");
        assert!(error.contains("give --gyro-unit as the sketch prints them"), "{error}");
    }

    #[test]
    fn a_gyro_in_counts_read_as_deg_per_s_is_named_before_the_positions_are_blamed() {
        let log = read(Sketch::Csv, gyro_in(GyroUnit::DegPerS)).unwrap();
        let Err(StreamFitError::GyroUnit(words)) = report(&log) else { panic!("fitted or blamed the periods") };
        assert!(words.contains("not in the given unit deg/s"), "{words}");
        assert!(words.contains("give --gyro-unit counts-250dps"), "{words}");
        for sketch in [Sketch::Csv, Sketch::Plotter, Sketch::Kalibr, Sketch::SerialPlotter] {
            let log = read(sketch, StreamOptions::default()).unwrap();
            assert_eq!(gyro_doubt(&log), None, "{sketch:?}");
        }
    }

    #[test]
    fn a_gyro_range_or_radians_read_wrong_is_named_by_the_turns_not_blamed_on_a_moved_board() {
        let named = |sketch, unit| {
            let turns = report(&read(sketch, gyro_in(unit)).unwrap()).unwrap().gyro_turns.unwrap();
            turns.fit.unwrap_err()
        };
        let eightfold = named(Sketch::Csv, GyroUnit::Counts2000);
        assert!(eightfold.contains("not in the given unit counts-2000dps"), "{eightfold}");
        assert!(
            eightfold.contains("give --gyro-unit counts-250dps") && !eightfold.contains("board moved"),
            "{eightfold}"
        );
        let radians = named(Sketch::Kalibr, GyroUnit::DegPerS);
        assert!(radians.contains("give --gyro-unit rad/s") && !radians.contains("turned only"), "{radians}");
        let right = report(&read(Sketch::Csv, StreamOptions::default()).unwrap()).unwrap().gyro_turns.unwrap();
        assert!(right.fit.is_ok(), "{:?}", right.fit);
    }
}
