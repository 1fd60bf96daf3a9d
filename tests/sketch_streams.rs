//! Calibrating from the stream a person's own sketch prints (issue 24): a simulated person turns the
//! realistic simulated sensor through an order of their own for about three minutes (faces, corners
//! and four edges), each of eight sketches prints it as it would, and `accelcal fit LOG`'s code path
//! (dialect, units, still periods, `ortho9` on the means of those at faces and corners, the edges held
//! out to verify it; the live `calibrate --port` fits its kept log with the same code) calibrates
//! from the log with no flag. The calibration is judged against the sensor's true errors, | |a| - 1 g |
//! rms over the sphere, over 10 sessions per sketch; the bounds are 1.3x what the issue measured for a
//! good tool (every still period averaged, `ortho9` on them all) on the same streams.
//!
//! Simulated clock: the sessions are generated and read faster than real time (the real-pace replay on
//! a pseudo-terminal is in host/tests/sketch_pty.rs).

use accelcal::data::Dataset;
use accelcal::fit::{self, Fit, FitOptions, Model, ModelChoice};
use accelcal::noise::stream::longest_still;
use accelcal::noise::stream::StillRecordError;
use accelcal::report::stream::StreamReport;
use accelcal::sim::person::PersonSession;
use accelcal::sim::sketch::Sketch;
use accelcal::stream::{cost, Dialect, DropReason, StillPeriods, StreamLog, StreamOptions};
use firmware::sim::physics::TrueErrors;
use shared::linalg::{mul_vec, norm, sub};

/// Sessions per sketch.
const SESSIONS: u64 = 10;
/// How far an entry of the gyro's G fitted from the turns may be from the true one.
const G_TOLERANCE: f64 = 0.002;

/// The issue's bounds in mg: (mean, worst) of the sessions' rms error; `None` for the Serial Plotter,
/// whitespace and Kalibr streams and issue 39's twelve, on which the issue measured no good tool: they
/// are held to 1.3x the good tool measured here on the same sessions.
fn bounds(sketch: Sketch) -> Option<(f64, f64)> {
    match sketch {
        Sketch::I2cdevlib => Some((0.83, 1.17)),
        Sketch::Motioncal => Some((0.33, 0.48)),
        Sketch::Plotter => Some((0.12, 0.16)),
        Sketch::Csv => Some((0.10, 0.15)),
        Sketch::Micropython => Some((0.57, 0.73)),
        _ => None,
    }
}

/// What the issue's good tool does: every still period averaged, `ortho9` on them all.
fn good_tool(log: &StreamLog) -> Fit {
    let still = StillPeriods::of(log);
    let rows = still.dataset.rows.iter().chain(&still.held_out.rows).cloned().collect();
    let options = FitOptions { g: 1.0, ..FitOptions::default() };
    fit::fit(&Dataset { rows }, ModelChoice::Only(Model::Ortho9), &options).expect("the good tool fits")
}

fn dialect(sketch: Sketch) -> Dialect {
    match sketch {
        Sketch::I2cdevlib => Dialect::I2cdevlib,
        Sketch::Motioncal => Dialect::Motioncal,
        Sketch::Plotter => Dialect::AdafruitPlotter,
        Sketch::Csv => Dialect::Csv,
        Sketch::Micropython => Dialect::Micropython,
        Sketch::SerialPlotter => Dialect::SerialPlotter,
        Sketch::Whitespace => Dialect::Whitespace,
        Sketch::Kalibr => Dialect::Kalibr,
        Sketch::Playground => Dialect::Labelled,
        Sketch::BasicReadings | Sketch::Esphome | Sketch::EspIdf | Sketch::Kriswiner => Dialect::MultiLine,
        Sketch::Esp32Json | Sketch::MicropythonDict => Dialect::Json,
        Sketch::CrOnly => Dialect::Csv,
        Sketch::SemicolonCsv => Dialect::SemicolonCsv,
        Sketch::Array => Dialect::Array,
        Sketch::Grouped => Dialect::Labelled,
        Sketch::Registers => Dialect::Whitespace,
    }
}

/// Directions spread evenly over the sphere (a Fibonacci lattice).
fn sphere(n: usize) -> Vec<[f64; 3]> {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..n)
        .map(|i| {
            let z = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
            let r = (1.0 - z * z).sqrt();
            [r * (golden * i as f64).cos(), r * (golden * i as f64).sin(), z]
        })
        .collect()
}

/// The calibration's | |a| - 1 g | rms over the sphere against the true sensor, in mg.
fn true_error_mg(fit: &Fit, truth: &TrueErrors, per_g: f64) -> f64 {
    let errors: Vec<f64> = sphere(500)
        .into_iter()
        .map(|up| {
            let reading = truth.reading_g(up.map(|v| v as f32)).map(|v| f64::from(v) * per_g);
            norm(mul_vec(&fit.matrix, sub(reading, fit.offset))) - 1.0
        })
        .collect();
    (errors.iter().map(|e| e * e).sum::<f64>() / errors.len() as f64).sqrt() * 1e3
}

/// One session's true error in mg: accelcal's, and the good tool's.
fn session_error(sketch: Sketch, seed: u64) -> (f64, f64) {
    let session = PersonSession::new(seed, sketch.reading());
    let minutes = session.samples.last().map_or(0.0, |s| s.at_s) / 60.0;
    // NOTE: a sketch printing every 500 ms ends its last hold up to a sample later.
    assert!((2.8..=3.3).contains(&minutes), "a session of {minutes:.2} minutes, not about three");
    let text: String = sketch.lines(&session).into_iter().map(|l| l.text).collect();
    let log = StreamLog::parse(&text, &StreamOptions::default()).expect("every sketch's log is read with no flag");
    assert_eq!(log.layout.dialect, dialect(sketch));
    let report = StreamReport::new(&log, ModelChoice::Only(Model::Ortho9), &Default::default()).expect("fits");
    let verification = report.verification.as_ref().expect("the edges verify the calibration");
    assert_eq!(verification.positions, 4, "{sketch:?} seed {seed}: the four edges are the fresh orientations");
    let error = true_error_mg(&report.fit.fit, &session.truth, sketch.accel_per_g());
    let good = true_error_mg(&good_tool(&log), &session.truth, sketch.accel_per_g());
    eprintln!(
        "{sketch:?} seed {seed}: {} segments, {error:.3} mg (good tool {good:.3}); verified {:.3} mg, floor {:.3} mg",
        report.segments.len(),
        verification.after_rms_mg,
        verification.noise_floor_mg
    );
    (error, good)
}

fn mean_and_worst(errors: &[f64]) -> (f64, f64) {
    (errors.iter().sum::<f64>() / errors.len() as f64, errors.iter().copied().fold(0.0, f64::max))
}

#[test]
fn each_sketchs_stream_calibrates_within_the_issues_bounds_over_ten_sessions() {
    let mut failures = Vec::new();
    for sketch in Sketch::ALL {
        let (errors, good): (Vec<f64>, Vec<f64>) = (1..=SESSIONS).map(|seed| session_error(sketch, seed)).unzip();
        let ((mean, worst), (good_mean, good_worst)) = (mean_and_worst(&errors), mean_and_worst(&good));
        let (mean_bound, worst_bound) = bounds(sketch).unwrap_or((1.3 * good_mean, 1.3 * good_worst));
        eprintln!(
            "{sketch:?}: mean {mean:.3} mg (bound {mean_bound:.3}), worst {worst:.3} mg (bound {worst_bound:.3}); \
             good tool {good_mean:.3}, {good_worst:.3}"
        );
        if mean > mean_bound || worst > worst_bound {
            failures.push(format!("{sketch:?}: mean {mean:.3}, worst {worst:.3}"));
        }
    }
    assert!(failures.is_empty(), "{failures:?}");
}

/// One session of `sketch`, printed and read back.
fn session_log(sketch: Sketch, seed: u64) -> (PersonSession, String, StreamLog) {
    let session = PersonSession::new(seed, sketch.reading());
    let text: String = sketch.lines(&session).into_iter().map(|l| l.text).collect();
    let log = StreamLog::parse(&text, &StreamOptions::default()).expect("read with no flag");
    (session, text, log)
}

#[test]
fn every_line_that_is_not_a_sample_is_counted_with_its_reason() {
    let (session, _, log) = session_log(Sketch::Motioncal, 1);
    let samples = session.samples.len();
    assert_eq!(log.samples.len(), samples);
    // After every Raw: line a Uni: line, every 50th also Cal1: and Cal2:; two lines before the data.
    assert_eq!(log.dropped.count(DropReason::SideRecord), samples + 2 * (samples / 50));
    assert_eq!(log.dropped.count(DropReason::Text), 2);
    let (_, _, csv) = session_log(Sketch::Csv, 1);
    assert_eq!((csv.dropped.count(DropReason::Header), csv.dropped.count(DropReason::Text)), (1, 7));
    assert_eq!(csv.rate.map(|r| (r.hz * 1000.0).round() / 1000.0), Some(100.0), "from the millis column");
}

#[test]
fn what_each_stream_costs_is_said_with_its_numbers() {
    let costs = |sketch| {
        let (_, _, log) = session_log(sketch, 2);
        let segments = StillPeriods::of(&log).segments;
        cost::costs(&log, &segments).into_iter().map(|c| c.words).collect::<Vec<_>>().join("\n")
    };
    let i2cdevlib = costs(Sketch::I2cdevlib);
    assert!(i2cdevlib.contains("no timestamps") && i2cdevlib.contains("rate is unknown"), "{i2cdevlib}");
    let plotter = costs(Sketch::Plotter);
    assert!(plotter.contains("the gyro's values step by 0.57 deg/s"), "{plotter}");
    assert!(plotter.contains("no better than 0.29 deg/s"), "{plotter}");
    let csv = costs(Sketch::Csv);
    assert!(!csv.contains("folds in") && !csv.contains("timestamps"), "{csv}");
    // A 19 Hz stream read with its rate: the aliased noise and what it costs in capture time.
    let (_, text, _) = session_log(Sketch::Micropython, 2);
    let log = StreamLog::parse(&text, &StreamOptions { rate_hz: Some(19.0), ..StreamOptions::default() }).unwrap();
    let words: Vec<String> = cost::costs(&log, &StillPeriods::of(&log).segments).into_iter().map(|c| c.words).collect();
    let aliasing = words.iter().find(|w| w.contains("folds in")).expect("aliasing named");
    let scatter_mg: f64 = aliasing["each sample scatters ".len()..].split(' ').next().unwrap().parse().unwrap();
    assert!((8.0..=10.0).contains(&scatter_mg), "{aliasing}");
}

#[test]
fn a_file_of_single_samples_is_recognised_and_segmented_never_fitted_row_by_row() {
    let (session, _, log) = session_log(Sketch::Csv, 3);
    let rows: String = std::iter::once("x,y,z\n".to_owned())
        .chain(log.accel_g().iter().map(|a| format!("{:.5},{:.5},{:.5}\n", a[0], a[1], a[2])))
        .collect();
    let as_data = Dataset::from_reader(rows.as_bytes(), 1.0).unwrap();
    assert!(as_data.looks_like_samples(), "{} rows of single samples taken as positions", as_data.rows.len());
    let still = StillPeriods::of(&log);
    assert!(!still.dataset.looks_like_samples(), "the averaged periods are positions");
    let samples = StreamLog::parse(&rows, &StreamOptions::default()).unwrap();
    let report = StreamReport::new(&samples, ModelChoice::Only(Model::Ortho9), &Default::default()).unwrap();
    assert_eq!(report.segments.len(), 19);
    let error = true_error_mg(&report.fit.fit, &session.truth, 1.0);
    let (_, worst_bound) = bounds(Sketch::Csv).expect("the issue bounds the CSV stream");
    assert!(error <= worst_bound, "{error:.3} mg");
}

#[test]
fn a_stream_without_timestamps_gives_no_noise_figures_without_a_rate() {
    let (_, text, log) = session_log(Sketch::I2cdevlib, 4);
    assert!(matches!(longest_still(&log), Err(StillRecordError::NoStreamRate)));
    let given = StreamLog::parse(&text, &StreamOptions { rate_hz: Some(9.0), ..StreamOptions::default() }).unwrap();
    assert!(matches!(longest_still(&given), Err(StillRecordError::TooShort { .. })), "9 Hz rests are < 100 samples");
    let (_, _, csv) = session_log(Sketch::Csv, 4);
    let (segment, series) = longest_still(&csv).unwrap();
    assert_eq!((series.rate_hz.round(), series.axes[0].len()), (100.0, segment.samples));
}

/// Person 1's CSV log with the gyro's counts halved: the chip at +-500 deg/s (65.5 counts a deg/s).
fn csv_at_500_dps(text: &str) -> String {
    let halve = |line: &str| {
        let values: Vec<&str> = line.split(',').collect();
        let gyro = values[4..].iter().map(|v| v.parse::<i64>().map_or(v.to_string(), |c| (c / 2).to_string()));
        values[..4].iter().map(|v| v.to_string()).chain(gyro).collect::<Vec<_>>().join(",")
    };
    let data = |line: &str| line.split(',').count() == 7 && line.split(',').all(|v| v.trim().parse::<f64>().is_ok());
    text.lines().map(|l| if data(l) { halve(l) } else { l.to_owned() }).map(|l| l + "\n").collect()
}

#[test]
fn the_gyros_g_comes_from_the_turns_and_a_range_in_counts_is_checked_against_them() {
    for sketch in [Sketch::Csv, Sketch::Kalibr] {
        let (session, _, log) = session_log(sketch, 1);
        let report = StreamReport::new(&log, ModelChoice::Only(Model::Ortho9), &Default::default()).unwrap();
        let turns = report.gyro_turns.as_ref().expect("the stream has a gyro");
        let fit = turns.fit.as_ref().unwrap_or_else(|e| panic!("{sketch:?}: G not fitted: {e}"));
        let truth = session.truth.gyro_matrix;
        let worst =
            (0..9).map(|k| (fit.matrix[k / 3][k % 3] - f64::from(truth[k / 3][k % 3])).abs()).fold(0.0, f64::max);
        eprintln!(
            "{sketch:?}: {} turns, G {:?} (true {:?}), worst entry off by {worst:.5}, residual {:.3} deg",
            fit.turns, fit.matrix, truth, fit.residual_deg
        );
        assert!(worst <= G_TOLERANCE, "{sketch:?}: G off the true one by {worst:.5}");
    }
    let (_, text, log) = session_log(Sketch::Csv, 1);
    let confirmed = StreamReport::new(&log, ModelChoice::Only(Model::Ortho9), &Default::default()).unwrap();
    let range = confirmed.gyro_turns.and_then(|g| g.range).unwrap_or_default();
    assert!(range.starts_with("the turns confirm the gyro's range: counts-250dps"), "{range}");
    let at_500 = StreamLog::parse(&csv_at_500_dps(&text), &StreamOptions::default()).unwrap();
    let named = StreamReport::new(&at_500, ModelChoice::Only(Model::Ortho9), &Default::default()).unwrap();
    let range = named.gyro_turns.and_then(|g| g.range).unwrap_or_default();
    assert!(range.contains("the turns say the gyro prints counts-500dps, not the assumed counts-250dps"), "{range}");
    assert!(range.contains("give --gyro-unit counts-500dps"), "{range}");
    let (_, _, slow) = session_log(Sketch::I2cdevlib, 1);
    let coarse = StreamReport::new(&slow, ModelChoice::Only(Model::Ortho9), &Default::default()).unwrap();
    let turns = coarse.gyro_turns.unwrap();
    let why = turns.fit.err().unwrap_or_default();
    assert!(why.contains("too coarsely sampled") || why.contains("rate is unknown"), "{why}");
    // NOTE: tab-separated counts with no time (issue 39: at +-500 deg/s its bias came out half the
    // truth, marked only "assumed"): the range is asked for, with the flag and the sketch's call.
    let range = turns.range.unwrap_or_default();
    assert!(range.starts_with("the gyro's range is not settled"), "{range}");
    assert!(range.contains("the assumed counts-250dps: give --gyro-unit counts-250dps, counts-500dps"), "{range}");
}
