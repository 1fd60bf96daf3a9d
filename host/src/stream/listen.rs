//! Reading a live stream until its session is done: the port polled, Ctrl-C and the stream's
//! silence heeded, and once a second the core's look at the lines so far ([`super::status`]) told
//! to the person, the session kept when it holds another still period, and the run ended once
//! every face and corner is rested and enough fresh orientations are held.

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use accelcal_core::run::ending::Ended;

use super::live::{LiveStream, Silence};
use super::session::Kept;
use super::status::Progress;
use super::StreamOptions;
use crate::error::Error;
use crate::limits::LIVE_DETECTION_LINES;
use crate::procedure::Feedback;

/// How often the person is told where things stand, in seconds.
const STATUS_EVERY: Duration = Duration::from_secs(1);

/// How a live stream is watched.
pub(super) struct Watch<'a> {
    /// How its lines are read (units, rate).
    pub stream: &'a StreamOptions,
    /// The port's baud rate, named when nothing readable comes.
    pub baud: u32,
    /// Where the session stands: what it keeps, what ends it.
    pub progress: Progress,
}

/// Reads the stream, telling the person where things stand and keeping the session, until every
/// face and corner is rested and enough fresh orientations are held, the stream stops or goes
/// away, or Ctrl-C (`interrupt` set); why it ended. What was read is kept in any case.
pub(super) fn until_done(
    live: &mut LiveStream,
    mut watch: Watch,
    kept: &Kept,
    interrupt: &AtomicBool,
    feedback: &mut dyn Feedback,
) -> Result<Ended, Error> {
    let mut last_status = Instant::now();
    let mut warned = false;
    loop {
        if let Err(e) = live.poll(Duration::from_millis(200)) {
            return Ok(Ended::short(format!("the port went away ({e})")));
        }
        if interrupt.load(Ordering::SeqCst) {
            return Ok(Ended::interrupted());
        }
        match live.silence() {
            Silence::Stopped => return Ok(Ended::short("the stream stopped")),
            Silence::Unreadable { seconds, ended } if ended || !warned => {
                warned = true;
                let words = unreadable(seconds, watch.baud);
                match ended {
                    true => return Ok(Ended::short(words)),
                    false => feedback.say(&words),
                }
            }
            Silence::Unreadable { .. } => {}
            Silence::Talking => warned = false,
        }
        if live.lines().len() < LIVE_DETECTION_LINES || last_status.elapsed() < STATUS_EVERY {
            continue;
        }
        last_status = Instant::now();
        if let Some(done) = status(live, &mut watch, kept, feedback)? {
            return Ok(Ended::complete(done));
        }
    }
}

/// Tells the person where things stand and keeps the session when it holds another still period;
/// `Some` with why once done.
fn status(
    live: &LiveStream,
    watch: &mut Watch,
    kept: &Kept,
    feedback: &mut dyn Feedback,
) -> Result<Option<String>, Error> {
    let look = watch.progress.look(live.lines(), watch.stream);
    if let Some(line) = &look.line {
        feedback.say(line);
    }
    if let Some(log) = &look.keep {
        kept.save(log, None)?;
    }
    Ok(look.ends)
}

/// A stream whose bytes hold no line of numbers, in words, with the likely cause and the way out.
fn unreadable(seconds: f64, baud: u32) -> String {
    format!(
        "nothing readable for {seconds:.0} s: bytes come but no line of numbers, most likely the wrong baud rate \
         (read at {baud} Bd): give the sketch's Serial.begin rate as --baud (9600, 38400, 57600, 115200 ...)"
    )
}
