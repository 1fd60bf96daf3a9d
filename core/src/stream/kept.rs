//! What a session from a board's own stream keeps of its log: each still period it fits as a
//! capture in g (as the session file holds it, in f32), and the stream as it was read. A stream's
//! printed, certified and exported calibration are one computation: the report fits
//! [`fitted_rows`], which are the kept session's own rows (`Session::dataset`), so the session's
//! outcome (the certificate's, the export's, the report's) is the fit the stream command printed.

use shared::protocol::CaptureStats;

use super::guide::nearest_name;
use super::log::StreamLog;
use super::still::StillPeriods;
use crate::data::{Dataset, Row};
use crate::session::{CaptureRecord, Session, SessionKind, StreamSource, Verification};

/// The session of `log` so far, begun at `began_unix_s` (seconds since the Unix epoch) on `source`'s
/// port, log and serial: its training still periods as captures, what the stream was read as, and
/// the verification once made.
pub fn session(
    log: &StreamLog,
    still: &StillPeriods,
    source: &StreamSource,
    began_unix_s: f64,
    verification: Option<Verification>,
) -> Session {
    let stream = StreamSource {
        dialect: log.layout.dialect.name().to_owned(),
        input_unit: log.accel_unit.name().to_owned(),
        gyro_unit: log.gyro_unit.map(|(unit, _)| unit.name().to_owned()),
        rate_hz: log.rate.map(|r| r.hz),
        ..source.clone()
    };
    let captures = captures(log, still, began_unix_s);
    Session { kind: SessionKind::Stream, captures, verification, stream: Some(stream), ..Session::default() }
}

/// The rows a stream's calibration is fitted to, in g: the captures its session keeps, as
/// `Session::dataset` gives them, each under the line of the log its still period begins at.
pub fn fitted_rows(log: &StreamLog, still: &StillPeriods) -> Dataset {
    let kept = Session { kind: SessionKind::Stream, captures: captures(log, still, 0.0), ..Session::default() };
    let mut fitted = kept.dataset();
    for (row, period) in fitted.rows.iter_mut().zip(&still.dataset.rows) {
        row.line = period.line;
    }
    fitted
}

/// The training still periods of `log` as captures taken at `unix_time_s`.
// NOTE: the periods held out at fresh orientations are in the verification, not the captures:
// the session's fit is the stream's.
fn captures(log: &StreamLog, still: &StillPeriods, unix_time_s: f64) -> Vec<CaptureRecord> {
    still.dataset.rows.iter().map(|row| capture(row, log, unix_time_s)).collect()
}

/// A still period (its mean in the stream's unit) as a capture, in g.
fn capture(row: &Row, log: &StreamLog, unix_time_s: f64) -> CaptureRecord {
    let per_g = log.accel_unit.per_g();
    let mean_g = row.reading.map(|v| v / per_g);
    let samples = row.count.unwrap_or(0);
    let stats = CaptureStats {
        samples,
        seconds: log.rate.map_or(0.0, |r| f64::from(samples) / r.hz) as f32,
        mean_g: mean_g.map(|v| v as f32),
        std_g: row.std.unwrap_or([0.0; 3]).map(|v| (v / per_g) as f32),
        gyro_mean_dps: row.gyro_mean_dps.unwrap_or([0.0; 3]).map(|v| v as f32),
        gyro_std_dps: [0.0; 3],
        // NOTE: a stream carries no temperature; `Session::dataset` leaves it out of the rows.
        temp_c: 0.0,
        clipped: 0,
        range: log.accel_unit.range(),
    };
    let name = format!("{} from line {}", nearest_name(mean_g), row.line);
    CaptureRecord { name, target: None, face: None, unix_time_s, stats, closing: false }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fit::FitOptions;
    use crate::report::stream::StreamReport;
    use crate::sim::person::PersonSession;
    use crate::sim::sketch::Sketch;
    use crate::stream::StreamOptions;
    use shared::protocol::SensorConfig;

    #[test]
    fn every_sketchs_printed_calibration_is_its_kept_sessions_outcome_bit_for_bit() {
        for sketch in Sketch::ALL {
            let person = PersonSession::new(1, sketch.reading());
            let text: String = sketch.lines(&person).into_iter().map(|line| line.text).collect();
            let log = StreamLog::parse(&text, &StreamOptions::default()).unwrap();
            let still = StillPeriods::of(&log);
            let source = StreamSource::for_tests(None, None);
            let begun = session(&log, &still, &source, 0.0, None);
            // What `calibrate --port` prints and keeps (and `fit LOG --model ortho9` gives again).
            let printed = StreamReport::new(&log, begun.model(), &FitOptions::default()).unwrap();
            let kept = session(&log, &still, &source, 0.0, printed.verification.clone());
            let outcome = kept.outcome(SensorConfig::default()).unwrap();
            let (printed, kept) = (printed.fit.fit, outcome.fit.in_unit(log.accel_unit.per_g()));
            assert_eq!((printed.matrix, printed.offset), (kept.matrix, kept.offset), "{sketch:?}");
            assert_eq!(printed.parameters, kept.parameters, "{sketch:?}");
            assert_eq!((printed.cost, printed.iterations), (kept.cost, kept.iterations), "{sketch:?}");
        }
    }
}
