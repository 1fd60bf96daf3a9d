//! Calibrating from the stream a person's own sketch prints (issue 24): a simulated person turns the
//! realistic simulated sensor through an order of their own for about three minutes, each of five
//! sketches prints it as it would, and `accelcal fit LOG`'s code path (dialect, units, still periods,
//! `ortho9` on their means) calibrates from the log with no flag. The calibration is judged against
//! the sensor's true errors, | |a| - 1 g | rms over the sphere, over 10 sessions per sketch; the bounds
//! are 1.3x what the issue measured for a good tool on the same streams.
//!
//! Simulated clock: the sessions are generated and read faster than real time (the real-pace replay on
//! a pseudo-terminal is in host/tests/sketch_pty.rs).

use accelcal::data::Dataset;
use accelcal::fit::{Model, ModelChoice};
use accelcal::noise::input::NoiseInputError;
use accelcal::noise::stream::longest_still;
use accelcal::report::stream::StreamReport;
use accelcal::sim::person::PersonSession;
use accelcal::sim::sketch::Sketch;
use accelcal::stream::{cost, Dialect, DropReason, StillPeriods, StreamLog, StreamOptions};
use firmware::sim::physics::TrueErrors;
use shared::linalg::{mul_vec, norm, sub};

/// Sessions per sketch.
const SESSIONS: u64 = 10;

/// The issue's bounds in mg: (mean, worst) of the sessions' rms error. The issue measured no good
/// tool on the Serial Plotter, whitespace and Kalibr streams: each is held to the bounds of the
/// issue's stream it is like (filtered, 50 Hz: the plotter's; filtered, 100 Hz or more: the CSV's).
fn bounds(sketch: Sketch) -> (f64, f64) {
    match sketch {
        Sketch::I2cdevlib => (0.83, 1.17),
        Sketch::Motioncal => (0.33, 0.48),
        Sketch::Plotter | Sketch::SerialPlotter => (0.12, 0.16),
        Sketch::Csv | Sketch::Whitespace | Sketch::Kalibr => (0.10, 0.15),
        Sketch::Micropython => (0.57, 0.73),
    }
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
fn true_error_mg(report: &StreamReport, truth: &TrueErrors, per_g: f64) -> f64 {
    let fit = &report.fit.fit;
    let errors: Vec<f64> = sphere(500)
        .into_iter()
        .map(|up| {
            let reading = truth.reading_g(up.map(|v| v as f32)).map(|v| f64::from(v) * per_g);
            norm(mul_vec(&fit.matrix, sub(reading, fit.offset))) - 1.0
        })
        .collect();
    (errors.iter().map(|e| e * e).sum::<f64>() / errors.len() as f64).sqrt() * 1e3
}

fn session_error(sketch: Sketch, seed: u64) -> f64 {
    let session = PersonSession::new(seed, sketch.reading());
    let minutes = session.samples.last().map_or(0.0, |s| s.at_s) / 60.0;
    assert!((2.8..=3.2).contains(&minutes), "a session of {minutes:.2} minutes, not about three");
    let text: String = sketch.lines(&session).into_iter().map(|l| l.text).collect();
    let log = StreamLog::parse(&text, &StreamOptions::default()).expect("every sketch's log is read with no flag");
    assert_eq!(log.layout.dialect, dialect(sketch));
    let report = StreamReport::new(&log, ModelChoice::Only(Model::Ortho9), &Default::default()).expect("fits");
    let error = true_error_mg(&report, &session.truth, sketch.accel_per_g());
    eprintln!(
        "{sketch:?} seed {seed}: {} segments, {error:.3} mg {:?}",
        report.segments.len(),
        report.segments.iter().map(|s| s.samples).collect::<Vec<_>>()
    );
    error
}

#[test]
fn each_sketchs_stream_calibrates_within_the_issues_bounds_over_ten_sessions() {
    let mut failures = Vec::new();
    for sketch in Sketch::ALL {
        let errors: Vec<f64> = (1..=SESSIONS).map(|seed| session_error(sketch, seed)).collect();
        let mean = errors.iter().sum::<f64>() / errors.len() as f64;
        let worst = errors.iter().copied().fold(0.0, f64::max);
        let (mean_bound, worst_bound) = bounds(sketch);
        eprintln!("{sketch:?}: mean {mean:.3} mg (bound {mean_bound}), worst {worst:.3} mg (bound {worst_bound})");
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
    let error = true_error_mg(&report, &session.truth, 1.0);
    assert!(error <= bounds(Sketch::Csv).1, "{error:.3} mg");
}

#[test]
fn a_stream_without_timestamps_gives_no_noise_figures_without_a_rate() {
    let (_, text, log) = session_log(Sketch::I2cdevlib, 4);
    assert!(matches!(longest_still(&log), Err(NoiseInputError::NoStreamRate)));
    let given = StreamLog::parse(&text, &StreamOptions { rate_hz: Some(9.0), ..StreamOptions::default() }).unwrap();
    assert!(matches!(longest_still(&given), Err(NoiseInputError::TooShort { .. })), "9 Hz rests are < 100 samples");
    let (_, _, csv) = session_log(Sketch::Csv, 4);
    let (segment, series) = longest_still(&csv).unwrap();
    assert_eq!((series.rate_hz.round(), series.axes[0].len()), (100.0, segment.samples));
}
