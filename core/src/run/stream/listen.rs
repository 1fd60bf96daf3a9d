//! A live stream listened to until its session is done: the port read, Ctrl-C and the stream's
//! silence heeded, and once a second by the host's time the core's look at the lines so far
//! ([`Progress::look`]) told to the person, the session kept when it holds another still period,
//! and the run ended once every face and corner is rested and enough fresh orientations are held,
//! or refused as a stream in another unit.

use super::{CalibrateOptions, Keep, Keeping, StreamPort};
use crate::limits::LIVE_DETECTION_LINES;
use crate::run::ending::Ended;
use crate::run::stop_rule::{Noise, StopRule};
use crate::run::Feedback;
use crate::session::SessionError;
use crate::stream::arrival::{Arrivals, Silence};
use crate::stream::status::{Ends, Progress};
use crate::stream::{read_heard, text_without_samples, ARRIVAL_RATE_TAG};

/// How often the person is told where things stand, in seconds.
const STATUS_EVERY_S: f64 = 1.0;

/// The bytes one read of the port takes at most.
const READ_BYTES: usize = 1024;

/// A live stream session being listened to: its lines so far and where it stands.
pub struct Listening<'a> {
    options: &'a CalibrateOptions,
    /// Every line so far, with its arrival.
    arrivals: Arrivals,
    /// Where the session stands: what it keeps, what ends it.
    progress: Progress,
    /// When the person was last told where things stand, in the host's seconds.
    last_status_s: f64,
    /// Whether the person was told the stream is unreadable since it last was readable.
    warned: bool,
}

impl<'a> Listening<'a> {
    /// Begins with the lines `before` (a resumed session's log) and the bytes `heard` while the port
    /// was listened to; nothing kept yet, each position held until its mean is known to what the
    /// target needs.
    pub fn new(options: &'a CalibrateOptions, before: &str, heard: &[u8]) -> Self {
        let rule = StopRule { target_mg: options.target_mg, noise: Noise::Measured, rate_hz: 0 };
        let progress = Progress::new(rule.mean_std_g(), options.verify);
        let arrivals = Arrivals::begun(before, heard);
        Listening { options, arrivals, progress, last_status_s: 0.0, warned: false }
    }

    /// Reads `port`, telling the person where things stand and keeping the session (as `keeping`
    /// says), until every face and corner is rested and enough fresh orientations are held, the
    /// stream stops, goes away or is refused, or Ctrl-C; why it ended.
    pub async fn until_done<P: StreamPort>(
        &mut self,
        port: &mut P,
        keeping: &Keeping,
        feedback: &mut dyn Feedback,
        keep: Keep<'_>,
    ) -> Result<Ended, SessionError> {
        self.last_status_s = port.now_s();
        let mut buffer = [0u8; READ_BYTES];
        loop {
            match port.read(&mut buffer).await {
                Ok(count) => self.arrivals.take(&buffer[..count], port.now_s()),
                Err(gone) => return Ok(Ended::short(format!("the port went away ({gone})"))),
            };
            if port.interrupted() {
                return Ok(Ended::interrupted());
            }
            let now_s = port.now_s();
            if let Some(ended) = self.heed(self.arrivals.silence(now_s), feedback) {
                return Ok(ended);
            }
            if self.arrivals.lines.len() < LIVE_DETECTION_LINES || now_s - self.last_status_s < STATUS_EVERY_S {
                continue;
            }
            self.last_status_s = now_s;
            if let Some(ends) = self.status(keeping, feedback, keep)? {
                return Ok(ended(ends));
            }
        }
    }

    /// What the stream's silence ends, when it does; an unreadable stream is named once while it
    /// stays unreadable.
    fn heed(&mut self, silence: Silence, feedback: &mut dyn Feedback) -> Option<Ended> {
        match silence {
            Silence::Stopped => return Some(Ended::short("the stream stopped")),
            Silence::Unreadable { seconds, ended } if ended || !self.warned => {
                self.warned = true;
                let words = unreadable(seconds, self.options.baud, &self.arrivals.lines);
                match ended {
                    true => return Some(Ended::short(words)),
                    false => feedback.say(&words),
                }
            }
            Silence::Unreadable { .. } => {}
            Silence::Talking => self.warned = false,
        }
        None
    }

    /// Tells the person where things stand and keeps the session when it holds another still period;
    /// why the run ends, once it does.
    fn status(
        &mut self,
        keeping: &Keeping,
        feedback: &mut dyn Feedback,
        keep: Keep<'_>,
    ) -> Result<Option<Ends>, SessionError> {
        let look = self.progress.look(&self.arrivals.lines, &self.options.stream);
        if let Some(line) = &look.line {
            feedback.say(line);
        }
        if let Some(log) = &look.keep {
            keep(&keeping.session(log, None))?;
        }
        Ok(look.ends)
    }

    /// What the log is closed with: the line not yet ended, ended, and the rate at which the lines
    /// that are samples arrived, when known (`fit LOG` reads it back).
    pub fn closing(&self) -> String {
        let log = read_heard(&self.arrivals.lines, &self.options.stream);
        let data: Vec<usize> = log.map(|log| log.samples.iter().map(|s| s.line - 1).collect()).unwrap_or_default();
        let mut closing = String::from(if self.arrivals.has_pending() { "\n" } else { "" });
        if let Some(hz) = self.arrivals.rate_hz(&data) {
            closing += &format!("{ARRIVAL_RATE_TAG} {hz:.4} Hz\n");
        }
        closing
    }
}

/// How a run the stream's status ends ended: done is complete, a refused stream is cut short (never
/// certified: its values are not in the unit they were read in).
fn ended(ends: Ends) -> Ended {
    match ends {
        Ends::Done(why) => Ended::complete(why),
        Ends::Refused(why) | Ends::Stalled(why) => Ended::short(why),
    }
}

/// The last lines looked at to say why a stream is unreadable.
const UNREADABLE_QUOTED_LINES: usize = 20;

/// A stream whose bytes hold no line of numbers, in words, with the likely cause and the way out:
/// lines of text that hold no sample are named as such (quoted, with the change to the sketch),
/// bytes that are not text as the wrong baud rate.
fn unreadable(seconds: f64, baud: u32, lines: &[(String, f64)]) -> String {
    let last: Vec<&str> = lines.iter().rev().take(UNREADABLE_QUOTED_LINES).rev().map(|(l, _)| l.as_str()).collect();
    if let Some(why) = text_without_samples(&last) {
        return format!("nothing readable for {seconds:.0} s: lines of text come but none holds a sample: {why}");
    }
    format!(
        "nothing readable for {seconds:.0} s: bytes come but no line of numbers, most likely the wrong baud rate \
         (read at {baud} Bd): give the sketch's Serial.begin rate as --baud (9600, 38400, 57600, 115200 ...)"
    )
}
