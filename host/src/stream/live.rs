//! A port that talks on its own, read line by line with each line's arrival time, every line kept
//! in a log file as it comes (so Ctrl-C or a pulled cable loses nothing, and `accelcal fit LOG`
//! reads exactly what the live session read). Nothing is ever written to the port. The lines and
//! the silence are judged by the core ([`Arrivals`]); this reads the port and the clock.

use std::io::{ErrorKind, Read, Write};
use std::time::{Duration, Instant};

pub use accelcal_core::stream::arrival::{arrival_hz, Arrivals, Silence};
use accelcal_core::stream::ARRIVAL_RATE_TAG;

use crate::link::{Port, TalkingPort};

/// A live stream and its log.
pub struct LiveStream {
    port: Box<dyn Port>,
    /// The lines so far, each with its arrival.
    pub arrivals: Arrivals,
    start: Instant,
    log: std::fs::File,
}

impl LiveStream {
    /// Starts from the lines `before` (a resumed session's log, already in `log`) and what was
    /// heard while listening, keeping lines in `log`.
    pub fn new(talking: TalkingPort, log: std::fs::File, before: &str) -> std::io::Result<Self> {
        let mut live =
            LiveStream { port: talking.port, arrivals: Arrivals::resumed(before), start: Instant::now(), log };
        live.take(&talking.heard)?;
        live.arrivals.forget_times();
        Ok(live)
    }

    /// Every complete line so far, with its arrival in seconds since listening began.
    pub fn lines(&self) -> &[(String, f64)] {
        &self.arrivals.lines
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
        Ok(self.arrivals.take(bytes, self.start.elapsed().as_secs_f64()))
    }

    /// What the stream's silence says now.
    pub fn silence(&self) -> Silence {
        self.arrivals.silence(self.start.elapsed().as_secs_f64())
    }

    /// Closes the log with the rate of the lines `data` (indices) by their arrival, when known.
    pub fn finish(mut self, data: &[usize]) -> std::io::Result<Option<f64>> {
        let rate = self.arrivals.rate_hz(data);
        if self.arrivals.has_pending() {
            self.log.write_all(b"\n")?;
        }
        if let Some(hz) = rate {
            writeln!(self.log, "{ARRIVAL_RATE_TAG} {hz:.4} Hz")?;
        }
        self.log.flush()?;
        Ok(rate)
    }
}
