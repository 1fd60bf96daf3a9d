//! `accelcal calibrate --port P` on a board that prints its own stream: nothing is written to it;
//! its lines are read and kept in a log, the dialect found, the person told which way to turn and
//! how the board rests, the still periods averaged and fitted once the fit predicts the target (or
//! the stream stops, or Ctrl-C), with the same code as `accelcal fit LOG` on the log it kept.

use std::path::PathBuf;
use std::sync::atomic::Ordering;
use std::time::{Duration, Instant};

use super::args::CalibrateArgs;
use super::calibrate::interrupt_on_ctrl_c;
use crate::error::Error;
use crate::fit::{FitOptions, Model, ModelChoice};
use crate::link::TalkingPort;
use crate::report::stream::{self, StreamReport};
use crate::stream::guide::next_turn;
use crate::stream::live::{arrival_hz, LiveStream};
use crate::stream::segment::mean_std;
use crate::stream::timing::{Rate, RateSource};
use crate::stream::{Layout, LineReader, StreamLog, StreamOptions};

/// A stream silent this long has stopped (long enough that a busy machine's pause is not taken for it).
const QUIET_S: f64 = 10.0;
/// Lines heard before the dialect is decided.
const DETECT_LINES: usize = 40;
/// Still periods before the stop rule is asked.
const MIN_PERIODS: usize = 12;
/// How often the person is told where things stand, in seconds.
const STATUS_EVERY: Duration = Duration::from_secs(1);

/// Calibrates from the stream of `talking`.
pub(super) fn calibrate_from_stream(args: &CalibrateArgs, talking: TalkingPort) -> Result<(), Error> {
    let path = args.stream_log.clone().unwrap_or_else(default_log);
    let unwritable = |source| Error::WriteFile { path: path.clone(), source };
    let file = std::fs::File::create(&path).map_err(unwritable)?;
    eprintln!(
        "{} prints its own stream: accelcal writes nothing to it and keeps what it prints in {}",
        talking.path,
        path.display()
    );
    let mut live = LiveStream::new(talking, file).map_err(unwritable)?;
    let options = args.stream.options(None);
    let why = listen_until_done(&mut live, &options, args.length.target_mg);
    let data = data_lines(&live);
    live.finish(&data).map_err(unwritable)?;
    eprintln!("{why}: fitting the still periods of {}", path.display());
    report(args, &path, &options)
}

/// Reads the stream, telling the person where things stand, until the fit predicts the target,
/// the stream stops or goes away, or Ctrl-C; why it ended. What was read is kept in any case.
fn listen_until_done(live: &mut LiveStream, options: &StreamOptions, target_mg: f64) -> String {
    let interrupt = interrupt_on_ctrl_c();
    let mut last_status = Instant::now();
    let mut fitted_periods = 0;
    loop {
        if let Err(e) = live.poll(Duration::from_millis(200)) {
            return format!("the port went away ({e})");
        }
        if interrupt.load(Ordering::SeqCst) {
            return "stopped by Ctrl-C".to_owned();
        }
        if live.quiet_s() > QUIET_S {
            return "the stream stopped".to_owned();
        }
        if live.lines.len() < DETECT_LINES || last_status.elapsed() < STATUS_EVERY {
            continue;
        }
        last_status = Instant::now();
        if let Some(done) = status(live, options, target_mg, &mut fitted_periods) {
            return done.to_owned();
        }
    }
}

fn default_log() -> PathBuf {
    PathBuf::from(format!("accelcal-stream-{}.log", crate::session::unix_time_s() as u64))
}

/// The stream read so far, at the rate its lines arrived.
fn snapshot(live: &LiveStream, options: &StreamOptions) -> Option<StreamLog> {
    let layout = Layout::detect(live.lines.iter().map(|(text, _)| text.as_str())).ok()?;
    let mut reader = LineReader::new(layout.clone());
    let mut samples = Vec::new();
    let mut arrivals = Vec::new();
    let mut dropped = crate::stream::Dropped::default();
    for (index, (text, at)) in live.lines.iter().enumerate() {
        match reader.read(text) {
            Ok(sample) => {
                samples.push(sample);
                arrivals.push(*at);
            }
            Err(reason) => dropped.add(reason, index + 1),
        }
    }
    let rate = arrival_hz(&arrivals).map(|hz| Rate { hz, source: RateSource::ArrivalTimes });
    StreamLog::new(layout, samples, dropped, rate, options).ok()
}

/// Tells the person where things stand; `Some` once the fit predicts the target (fitted again
/// only when a still period was added since `fitted_periods`).
fn status(
    live: &LiveStream,
    options: &StreamOptions,
    target_mg: f64,
    fitted_periods: &mut usize,
) -> Option<&'static str> {
    let log = snapshot(live, options)?;
    let accel = log.accel_g();
    let recent = &accel[accel.len().saturating_sub(5)..];
    let (up, scatter) = mean_std(recent);
    let still = crate::stream::StillPeriods::of(&log);
    let rested: Vec<[f64; 3]> = still.segments.iter().map(|s| s.mean_g).collect();
    let moving = if scatter.iter().any(|&s| s > 0.05) { "moving" } else { "resting" };
    let tilt = up.map(|v| v / shared::linalg::norm(up));
    eprintln!(
        "{} {:.1} Hz: {} samples, {} still periods; {moving}, up = ({:+.2} {:+.2} {:+.2}); {}",
        log.layout.dialect.name(),
        log.rate.map_or(0.0, |r| r.hz),
        log.samples.len(),
        rested.len(),
        tilt[0],
        tilt[1],
        tilt[2],
        next_turn(up, &rested)
    );
    if rested.len() < MIN_PERIODS || rested.len() == *fitted_periods {
        return None;
    }
    *fitted_periods = rested.len();
    let report = StreamReport::new(&log, ModelChoice::Only(Model::Ortho9), &FitOptions::default()).ok()?;
    let predicted = report.fit.fit.prediction.as_ref()?.norm_error_mg;
    (predicted <= target_mg).then_some("the fit predicts the target")
}

/// The indices of the lines that carry samples.
fn data_lines(live: &LiveStream) -> Vec<usize> {
    let Ok(layout) = Layout::detect(live.lines.iter().map(|(t, _)| t.as_str())) else { return Vec::new() };
    let mut reader = LineReader::new(layout);
    live.lines.iter().enumerate().filter(|(_, (text, _))| reader.read(text).is_ok()).map(|(i, _)| i).collect()
}

/// The calibration of the kept log, as `fit LOG` gives it.
fn report(args: &CalibrateArgs, path: &std::path::Path, options: &StreamOptions) -> Result<(), Error> {
    let text = std::fs::read_to_string(path).map_err(|source| Error::ReadFile { path: path.to_owned(), source })?;
    let log = StreamLog::parse(&text, options).map_err(|source| Error::Stream { path: path.to_owned(), source })?;
    let report = StreamReport::new(&log, ModelChoice::Only(Model::Ortho9), &FitOptions::default())
        .map_err(|source| Error::StreamFit { path: path.to_owned(), source })?;
    if args.json {
        println!("{}", stream::json(&report));
    } else {
        print!("{}", stream::text(&report));
        println!(
            "kept in {}: `accelcal fit {} --model ortho9` gives this calibration again",
            path.display(),
            path.display()
        );
    }
    Ok(())
}
