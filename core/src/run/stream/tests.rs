//! The stream run's policies on a simulated person's sketch replayed in memory by a fake clock:
//! milliseconds, not a pseudo-terminal's minutes.

use std::cell::RefCell;

use embassy_futures::block_on;

use super::*;
use crate::run::ending::Ended;
use crate::run::Told;
use crate::sim::person::PersonSession;
use crate::sim::sketch::Sketch;
use crate::stream::{AccelUnit, GyroUnit, StreamError, ARRIVAL_RATE_TAG};

/// How far the fake clock moves with each read, in seconds (a binary fraction: whole seconds add up
/// exactly, as the host's 200 ms reads add up to its clock).
const READ_S: f64 = 0.25;

/// A port that replays timed bytes by a fake clock: each read waits [`READ_S`] and hands over what
/// came by then; Ctrl-C from `ctrl_c_at_s`; gone from `gone_at_s` (so that a run that would never
/// end, ends).
struct Replay {
    chunks: Vec<(f64, Vec<u8>)>,
    next: usize,
    waiting: Vec<u8>,
    now_s: f64,
    ctrl_c_at_s: f64,
    gone_at_s: f64,
    /// Every byte handed over: the log as the host keeps it.
    log: Vec<u8>,
}

impl Replay {
    fn of(chunks: Vec<(f64, Vec<u8>)>) -> Self {
        let (ctrl_c_at_s, gone_at_s) = (f64::INFINITY, 400.0);
        Replay { chunks, next: 0, waiting: Vec::new(), now_s: 0.0, ctrl_c_at_s, gone_at_s, log: Vec::new() }
    }
}

impl StreamPort for Replay {
    type Error = String;

    async fn read(&mut self, buffer: &mut [u8]) -> Result<usize, String> {
        self.now_s += READ_S;
        if self.now_s >= self.gone_at_s {
            return Err("unplugged".into());
        }
        while self.chunks.get(self.next).is_some_and(|(at_s, _)| *at_s <= self.now_s) {
            self.waiting.extend_from_slice(&self.chunks[self.next].1);
            self.next += 1;
        }
        let count = self.waiting.len().min(buffer.len());
        buffer[..count].copy_from_slice(&self.waiting[..count]);
        self.log.extend(self.waiting.drain(..count));
        Ok(count)
    }

    fn now_s(&self) -> f64 {
        self.now_s
    }

    fn interrupted(&self) -> bool {
        self.now_s >= self.ctrl_c_at_s
    }
}

/// A simulated person's three-minute session (faces, corners and four edges) as the CSV sketch
/// prints it, each line at the time it is printed.
fn person() -> Vec<(f64, Vec<u8>)> {
    let session = PersonSession::new(2, Sketch::I2cdevlib.reading());
    Sketch::I2cdevlib.lines(&session).into_iter().map(|line| (line.at_s, line.text.into_bytes())).collect()
}

/// Four fresh orientations wanted (the person's edges), the default target, a lot to go into.
fn options() -> CalibrateOptions {
    CalibrateOptions {
        stream: StreamOptions::default(),
        baud: 115_200,
        target_mg: crate::limits::DEFAULT_TARGET_MG,
        verify: 4,
        lot: Some("lot.sqlite".into()),
        json: false,
    }
}

fn keeping() -> Keeping {
    let source = StreamSource { log: "stream.log".into(), ..StreamSource::for_tests(None, None) };
    Keeping { json: "stream.json".into(), source, began_unix_s: 1.7e9 }
}

/// What a run left: how it ended and when, every session kept (and how many while listening),
/// what the person was told, what the log was closed with, and its end.
struct Ran {
    ended: Ended,
    ended_at_s: f64,
    kept: Vec<Session>,
    kept_listening: usize,
    told: Vec<String>,
    closing: String,
    finished: Result<Finished, StreamRunError>,
}

/// Listens to `port` until done, closes its log and finishes the run, as the host does.
fn run(mut port: Replay, options: &CalibrateOptions) -> Ran {
    let keeping = keeping();
    let (mut told, kept) = (Told(Vec::new()), RefCell::new(Vec::new()));
    let mut keep = |session: &Session| {
        kept.borrow_mut().push(session.clone());
        Ok(())
    };
    let mut listening = Listening::new(options, "", &[]);
    let ended = block_on(listening.until_done(&mut port, &keeping, &mut told, &mut keep)).unwrap();
    let closing = listening.closing();
    let kept_listening = kept.borrow().len();
    let text = String::from_utf8_lossy(&port.log).into_owned() + &closing;
    let finished = finish(&text, &ended, options, &keeping, &mut told, &mut keep);
    Ran { ended, ended_at_s: port.now_s, kept: kept.take(), kept_listening, told: told.0, closing, finished }
}

fn said(told: &[String], start: &str) -> Vec<String> {
    told.iter().filter(|line| line.starts_with(start)).cloned().collect()
}

#[test]
fn the_run_ends_complete_once_every_face_and_corner_rested_and_the_fresh_orientations_are_held() {
    let ran = run(Replay::of(person()), &options());
    assert_eq!(ran.ended, Ended::complete("every face and corner rested and 4 fresh orientations held"));
    assert!(ran.ended_at_s < 190.0, "the run waited {} s, past the person's session", ran.ended_at_s);
    let finished = ran.finished.expect("fitted");
    assert!(finished.certifies, "a complete run is not certified");
    assert_eq!(finished.session.verification.as_ref().map(|v| v.positions), Some(4));
    assert!(said(&ran.told, "no certificate").is_empty(), "{:?}", ran.told);
    let kept = "kept: the session in stream.json (`accelcal report stream.json`), every line in stream.log";
    assert!(finished.printed.contains(kept), "{}", finished.printed);
    assert!(ran.closing.starts_with(ARRIVAL_RATE_TAG), "the log closed without its rate: {:?}", ran.closing);
}

#[test]
fn the_session_is_kept_on_each_new_still_period_then_before_and_after_the_fit() {
    let ran = run(Replay::of(person()), &options());
    let last = ran.kept.last().expect("kept");
    let periods = last.captures.len() + last.verification.as_ref().map_or(0, |v| v.positions);
    // NOTE: a look once a second sees each still period (7.5-9.5 s rests) come on its own.
    assert_eq!(ran.kept_listening, periods, "kept while listening other than once per still period");
    assert_eq!(ran.kept.len(), ran.kept_listening + 2, "not kept once before the fit and once after");
    assert!(ran.kept[ran.kept_listening].verification.is_none() && ran.kept.last().unwrap().verification.is_some());
}

#[test]
fn a_status_line_is_told_once_a_second_by_the_ports_clock() {
    let mut port = Replay::of(person());
    port.ctrl_c_at_s = 60.0;
    let ran = run(port, &options());
    // NOTE: the first once 40 lines have come (the sketch's 3 and 37 samples at 9 Hz: at 4.25 s),
    // then each second until 59.25 s; the read at 60 s sees Ctrl-C.
    let status = said(&ran.told, "i2cdevlib ");
    assert_eq!(status.len(), 56, "{status:?}");
}

#[test]
fn ctrl_c_midway_ends_the_run_not_complete_fitted_but_not_certified() {
    let mut port = Replay::of(person());
    port.ctrl_c_at_s = 120.0;
    let ran = run(port, &options());
    assert_eq!((ran.ended.clone(), ran.ended_at_s), (Ended::interrupted(), 120.0));
    let finished = ran.finished.expect("enough still periods to fit");
    assert!(!finished.certifies, "a run stopped by Ctrl-C certifies");
    let resume = "`accelcal calibrate --port /dev/ttyUSB0 --resume stream.json --lot lot.sqlite` goes on with it";
    let no_certificate = said(&ran.told, "no certificate: the session ended before every face and corner was rested");
    assert!(no_certificate.len() == 1 && no_certificate[0].ends_with(resume), "{:?}", ran.told);
    assert!(said(&ran.told, "stopped by Ctrl-C: fitting the still periods of stream.log").len() == 1, "{:?}", ran.told);
}

#[test]
fn a_log_too_short_to_fit_keeps_its_session_before_the_fit_and_says_how_to_go_on() {
    let mut port = Replay::of(person());
    port.ctrl_c_at_s = 25.0;
    let ran = run(port, &options());
    assert!(matches!(ran.finished, Err(StreamRunError::Fit(_))), "fitted from 25 s");
    assert_eq!(ran.kept.len(), ran.kept_listening + 1, "the session was not kept before the fit");
    assert!(!ran.kept.last().unwrap().captures.is_empty());
    let resume = "the session is kept in stream.json: `accelcal calibrate --port /dev/ttyUSB0 --resume stream.json \
                  --lot lot.sqlite` goes on with it";
    assert_eq!(said(&ran.told, "the session is kept in"), [resume]);
}

#[test]
fn a_stream_that_stops_or_goes_away_ends_the_run_short() {
    let until = |end_s: f64| person().into_iter().filter(|(at_s, _)| *at_s < end_s).collect();
    let ran = run(Replay::of(until(110.0)), &options());
    assert_eq!(ran.ended, Ended::short("the stream stopped"));
    // NOTE: the last line came just before 110 s; silence past STREAM_QUIET_S (10 s) stops it.
    assert!((120.0..120.5).contains(&ran.ended_at_s), "stopped at {} s", ran.ended_at_s);
    assert!(!ran.finished.expect("fitted").certifies);
    let mut port = Replay::of(person());
    port.gone_at_s = 50.0;
    let ran = run(port, &options());
    assert_eq!((ran.ended, ran.ended_at_s), (Ended::short("the port went away (unplugged)"), 50.0));
}

#[test]
fn bytes_with_no_line_of_numbers_are_named_once_then_end_the_run() {
    // NOTE: 115200 Bd read at 38400: mostly high bytes, a newline now and then.
    let garbled: Vec<(f64, Vec<u8>)> =
        (0..300).map(|k| (f64::from(k) * 0.05, vec![0xf8, 0x80, 0x66, 0xfe, 0x1c, 0x78, 0x98, b'\n'])).collect();
    let ran = run(Replay::of(garbled), &options());
    let warned = said(&ran.told, "nothing readable for 5 s: bytes come but no line of numbers");
    assert_eq!(warned.len(), 1, "{:?}", ran.told);
    assert_eq!(said(&ran.told, "nothing readable for ").len(), 2, "warned more than once: {:?}", ran.told);
    assert!(warned[0].contains("(read at 115200 Bd): give the sketch's Serial.begin rate as --baud"), "{warned:?}");
    assert!(!ran.ended.complete && ran.ended.why.starts_with("nothing readable for 10 s"), "{:?}", ran.ended);
}

#[test]
fn a_stream_read_in_the_wrong_unit_ends_the_run_not_complete_and_uncertified() {
    let accel = StreamOptions { accel_unit: Some(AccelUnit::G), ..StreamOptions::default() };
    let gyro = StreamOptions { gyro_unit: Some(GyroUnit::DegPerS), ..StreamOptions::default() };
    for (stream, named) in [(accel, "give --input-unit counts-2g"), (gyro, "give --gyro-unit counts-250dps")] {
        let ran = run(Replay::of(person()), &CalibrateOptions { stream, ..options() });
        assert!(!ran.ended.complete, "a refused stream ended complete: {:?}", ran.ended);
        assert!(ran.ended.why.contains(named) && ran.ended_at_s < 30.0, "{:?} at {} s", ran.ended, ran.ended_at_s);
        assert!(ran.finished.as_ref().map_or(true, |f| !f.certifies), "a refused stream certifies");
    }
    let accel = StreamOptions { accel_unit: Some(AccelUnit::G), ..StreamOptions::default() };
    let ran = run(Replay::of(person()), &CalibrateOptions { stream: accel, ..options() });
    assert!(matches!(ran.finished, Err(StreamRunError::Log(StreamError::OtherAccelUnit { .. }))));
}

#[test]
fn the_log_is_closed_with_its_unended_line_ended_and_the_rate_its_samples_arrived_at() {
    let mut lines: Vec<(f64, Vec<u8>)> = person().into_iter().filter(|(at_s, _)| *at_s < 29.0).collect();
    lines.push((29.5, b"a/g:\t120\t-4".to_vec()));
    let mut port = Replay::of(lines);
    port.ctrl_c_at_s = 30.0;
    let closing = run(port, &options()).closing;
    let rate = closing.strip_prefix(&format!("\n{ARRIVAL_RATE_TAG} ")).and_then(|rest| rest.strip_suffix(" Hz\n"));
    let hz: f64 = rate.and_then(|hz| hz.parse().ok()).unwrap_or_else(|| panic!("closed with {closing:?}"));
    // NOTE: i2cdevlib's sketch prints at about 9 Hz; lines handed over in 0.25 s bursts.
    assert!((hz - 9.0).abs() < 0.3, "{hz} Hz");
}

#[test]
fn a_session_short_of_fresh_orientations_ends_with_what_it_has_and_says_so() {
    // NOTE: the person holds four edges; six are wanted. After the session the board rests where it
    // was left and the sketch goes on printing: no new still period comes.
    let mut chunks = person();
    let (last_s, last_line) = chunks.last().cloned().unwrap();
    chunks.extend((1..=1000).map(|k| (last_s + f64::from(k) * 0.11, last_line.clone())));
    let ran = run(Replay::of(chunks), &CalibrateOptions { verify: 6, ..options() });
    assert!(!ran.ended.complete, "{:?}", ran.ended);
    assert!(ran.ended.why.starts_with("every face and corner rested but only 4 of the 6 fresh"), "{:?}", ran.ended);
    assert!(ran.ended.why.contains("fitted with what was held and not certified"), "{:?}", ran.ended);
    // NOTE: the last still period (the last hold, continued) began before the session's end.
    assert!(ran.ended_at_s > last_s && ran.ended_at_s < last_s + 75.0, "ended at {} s", ran.ended_at_s);
    assert!(!ran.finished.expect("fitted with what it has").certifies);
}

#[test]
fn lines_of_text_with_no_sample_are_named_with_a_line_quoted_and_the_fix_never_the_baud_rate() {
    let lines = |text: &str| (0..600).map(|k| (f64::from(k) * 0.1, text.as_bytes().to_vec())).collect::<Vec<_>>();
    let ran = run(Replay::of(lines("temp=21.5\r\n")), &options());
    assert!(ran.ended.why.contains(" lines came and none was read: none of the "), "{:?}", ran.ended);
    assert!(ran.ended.why.contains("line 1 `temp=21.5` holds 1 value (temp)"), "{:?}", ran.ended);
    assert!(ran.ended_at_s < 25.0, "ended at {} s", ran.ended_at_s);
    let ran = run(Replay::of(lines("Connecting to WiFi...\r\n")), &options());
    let warned = said(&ran.told, "nothing readable for 5 s: lines of text come but none holds a sample");
    assert_eq!(warned.len(), 1, "{:?}", ran.told);
    assert!(warned[0].contains("`Connecting to WiFi...`): another program's text or a log with no sensor"));
    assert!(ran.told.iter().chain([&ran.ended.why]).all(|line| !line.contains("baud")), "{:?}", ran.told);
}
