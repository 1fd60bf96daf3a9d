//! A port that talks on its own, read line by line with each line's arrival time, every line kept
//! in a log file as it comes (so Ctrl-C or a pulled cable loses nothing, and `accelcal fit LOG`
//! reads exactly what the live session read). Nothing is ever written to the port.

use std::io::{ErrorKind, Read, Write};
use std::time::{Duration, Instant};

use crate::link::{Port, TalkingPort};

/// The line a live session adds at the end of its log: the rate it measured from the lines'
/// arrival, for a stream without timestamps (`StreamLog::parse` reads it back).
pub const ARRIVAL_RATE_TAG: &str = "# accelcal: lines arrived at";

/// A live stream and its log.
pub struct LiveStream {
    port: Box<dyn Port>,
    pending: Vec<u8>,
    /// Every complete line so far, with its arrival in seconds since listening began.
    pub lines: Vec<(String, f64)>,
    start: Instant,
    log: std::fs::File,
}

impl LiveStream {
    /// Starts from the lines `before` (a resumed session's log, already in `log`) and what was
    /// heard while listening, keeping lines in `log`.
    pub fn new(talking: TalkingPort, log: std::fs::File, before: &str) -> std::io::Result<Self> {
        let lines = before.lines().map(|line| (line.to_owned(), 0.0)).collect();
        let mut live = LiveStream { port: talking.port, pending: Vec::new(), lines, start: Instant::now(), log };
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
        for &byte in bytes {
            if byte == b'\n' {
                let text = String::from_utf8_lossy(&self.pending).trim_end_matches('\r').to_owned();
                self.lines.push((text, now));
                self.pending.clear();
            } else {
                self.pending.push(byte);
            }
        }
        Ok(self.lines.len() - before)
    }

    /// Seconds since the last line came.
    pub fn quiet_s(&self) -> f64 {
        self.start.elapsed().as_secs_f64() - self.lines.last().map_or(0.0, |l| l.1)
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

/// The rate of lines that arrived at `times` (seconds; 0 for those heard while listening): their
/// count over their span, since a port hands over lines in bursts.
pub fn arrival_hz(times: &[f64]) -> Option<f64> {
    let timed: Vec<f64> = times.iter().copied().filter(|&t| t > 0.0).collect();
    match (timed.first(), timed.last()) {
        (Some(first), Some(last)) if last > first => Some((timed.len() - 1) as f64 / (last - first)),
        _ => None,
    }
}

/// The rate a live session's log recorded from the lines' arrival.
pub fn arrival_rate(text: &str) -> Option<f64> {
    let line = text.lines().rev().find(|l| l.starts_with(ARRIVAL_RATE_TAG))?;
    line[ARRIVAL_RATE_TAG.len()..].trim().trim_end_matches("Hz").trim().parse().ok()
}
