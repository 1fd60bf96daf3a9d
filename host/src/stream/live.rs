//! A port that talks on its own, read line by line with each line's arrival time, every line kept
//! in a log file as it comes (so Ctrl-C or a pulled cable loses nothing, and `accelcal fit LOG`
//! reads exactly what the live session read). Nothing is ever written to the port.

use std::io::{ErrorKind, Read, Write};
use std::time::{Duration, Instant};

use super::log::{text_of, ARRIVAL_RATE_TAG};
use crate::limits::{STREAM_QUIET_S, STREAM_UNREADABLE_S};
use crate::link::{Port, TalkingPort};

/// A live stream and its log.
pub struct LiveStream {
    port: Box<dyn Port>,
    pending: Vec<u8>,
    /// Every complete line so far, with its arrival in seconds since listening began.
    pub lines: Vec<(String, f64)>,
    start: Instant,
    log: std::fs::File,
    /// When the last bytes came, in seconds since listening began.
    last_bytes_s: f64,
    /// When the last line holding numbers came, in seconds since listening began.
    last_readable_s: f64,
}

/// What a live stream's silence says.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Silence {
    /// Lines of numbers keep coming (or not yet long without).
    Talking,
    /// Bytes still come but no line of numbers, for this many seconds: the wrong baud rate, most likely.
    Unreadable { seconds: f64, ended: bool },
    /// Nothing at all has come for [`STREAM_QUIET_S`]: the stream stopped.
    Stopped,
}

impl Silence {
    /// The silence of a stream whose last bytes came `quiet_s` ago and last line of numbers
    /// `unreadable_s` ago.
    pub fn judge(quiet_s: f64, unreadable_s: f64) -> Silence {
        match () {
            _ if quiet_s > STREAM_QUIET_S => Silence::Stopped,
            // NOTE: bytes in the later half of the stretch: a stream that stopped mid-line is not garbled.
            _ if unreadable_s > STREAM_UNREADABLE_S && quiet_s < unreadable_s / 2.0 => {
                Silence::Unreadable { seconds: unreadable_s, ended: unreadable_s > STREAM_QUIET_S }
            }
            _ => Silence::Talking,
        }
    }
}

impl LiveStream {
    /// Starts from the lines `before` (a resumed session's log, already in `log`) and what was
    /// heard while listening, keeping lines in `log`.
    pub fn new(talking: TalkingPort, log: std::fs::File, before: &str) -> std::io::Result<Self> {
        let lines = before.lines().map(|line| (line.to_owned(), 0.0)).collect();
        let start = Instant::now();
        let (last_bytes_s, last_readable_s) = (0.0, 0.0);
        let mut live =
            LiveStream { port: talking.port, pending: Vec::new(), lines, start, log, last_bytes_s, last_readable_s };
        live.take(&talking.heard)?;
        // NOTE: lines heard while listening came at unknown times: 0 keeps them out of the rate.
        live.lines.iter_mut().for_each(|line| line.1 = 0.0);
        Ok(live)
    }

    /// Reads what the port has sent within `wait`; the number of new lines.
    pub fn poll(&mut self, wait: Duration) -> std::io::Result<usize> {
        self.port.set_read_timeout(wait)?;
        let mut buffer = [0u8; 1024];
        match self.port.read(&mut buffer) {
            Ok(n) => self.take(&buffer[..n]),
            // NOTE: Ctrl-C interrupts the read: the caller sees it in its flag, not as a port gone.
            Err(e) if matches!(e.kind(), ErrorKind::TimedOut | ErrorKind::WouldBlock | ErrorKind::Interrupted) => Ok(0),
            Err(e) => Err(e),
        }
    }

    fn take(&mut self, bytes: &[u8]) -> std::io::Result<usize> {
        self.log.write_all(bytes)?;
        let now = self.start.elapsed().as_secs_f64();
        let before = self.lines.len();
        if !bytes.is_empty() {
            self.last_bytes_s = now;
        }
        for &byte in bytes {
            if byte == b'\n' {
                let text = text_of(&self.pending).trim_end_matches('\r').to_owned();
                if holds_numbers(&text) {
                    self.last_readable_s = now;
                }
                self.lines.push((text, now));
                self.pending.clear();
            } else {
                self.pending.push(byte);
            }
        }
        Ok(self.lines.len() - before)
    }

    /// What the stream's silence says now.
    pub fn silence(&self) -> Silence {
        let now = self.start.elapsed().as_secs_f64();
        Silence::judge(now - self.last_bytes_s, now - self.last_readable_s)
    }

    /// Closes the log with the rate of the lines `data` (indices) by their arrival, when known.
    pub fn finish(mut self, data: &[usize]) -> std::io::Result<Option<f64>> {
        let times: Vec<f64> = data.iter().map(|&i| self.lines[i].1).collect();
        let rate = arrival_hz(&times);
        if !self.pending.is_empty() {
            self.log.write_all(b"\n")?;
        }
        if let Some(hz) = rate {
            writeln!(self.log, "{ARRIVAL_RATE_TAG} {hz:.4} Hz")?;
        }
        self.log.flush()?;
        Ok(rate)
    }
}

/// Whether a line holds numbers as some dialect's samples do (its dialect aside): readable.
fn holds_numbers(text: &str) -> bool {
    !text.contains(char::REPLACEMENT_CHARACTER) && super::line::fields(text).is_ok()
}

/// The rate of lines that arrived at `times` (seconds; 0 for those heard while listening): their
/// count over their span, since a port hands over lines in bursts.
pub fn arrival_hz(times: &[f64]) -> Option<f64> {
    let timed: Vec<f64> = times.iter().copied().filter(|&t| t > 0.0).collect();
    match (timed.first(), timed.last()) {
        (Some(first), Some(last)) if last > first => Some((timed.len() - 1) as f64 / (last - first)),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stream::text_of;

    #[test]
    fn wrong_baud_bytes_are_unreadable_and_named_before_the_stream_counts_as_stopped() {
        // NOTE: 115200 Bd read at 38400: mostly high bytes, a few newlines (usertrial's junkfeed).
        let garbled = text_of(&[0xf8, 0x80, 0x66, 0xfe, 0x00, 0x1c, 0x78, 0x98, 0x9e, 0x06, 0xe0]);
        assert!(!holds_numbers(&garbled), "{garbled:?}");
        assert!(!holds_numbers("ets Jun  8 2016 00:22:57"));
        assert!(holds_numbers("90112,12449,-11115,-895,-152,96,53"));
        assert_eq!(Silence::judge(0.1, 2.0), Silence::Talking);
        assert_eq!(Silence::judge(0.1, 6.0), Silence::Unreadable { seconds: 6.0, ended: false });
        assert_eq!(Silence::judge(0.1, 10.5), Silence::Unreadable { seconds: 10.5, ended: true });
        assert_eq!(Silence::judge(6.0, 6.0), Silence::Talking, "a stream that stopped is not garbled");
        assert_eq!(Silence::judge(10.5, 10.5), Silence::Stopped);
    }
}
