//! A port that talks on its own, read as the core's stream run asks ([`StreamPort`]): its bytes
//! with the time they came, each kept in a log file as it comes (so Ctrl-C or a pulled cable loses
//! nothing, and `accelcal fit LOG` reads exactly what the live session read), and the Ctrl-C flag.
//! Nothing is ever written to the port. The lines and the silence are judged by the core
//! (`accelcal_core::run::stream`); this reads the port and the clock and writes the log.

use std::io::{ErrorKind, Read, Write};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use accelcal_core::run::stream::StreamPort;

use crate::link::{Port, TalkingPort};

/// How long one read waits: short enough that Ctrl-C and the status once a second are heeded promptly.
const READ_WAIT: Duration = Duration::from_millis(200);

/// A live stream and its log.
pub struct LiveStream<'a> {
    port: Box<dyn Port>,
    start: Instant,
    log: std::fs::File,
    interrupt: &'a AtomicBool,
}

impl<'a> LiveStream<'a> {
    /// Reads `talking`'s port, keeping in `log` what was heard while it was listened to and every
    /// byte from now on; stopped when `interrupt` is set (Ctrl-C).
    pub fn new(talking: TalkingPort, mut log: std::fs::File, interrupt: &'a AtomicBool) -> std::io::Result<Self> {
        log.write_all(&talking.heard)?;
        Ok(LiveStream { port: talking.port, start: Instant::now(), log, interrupt })
    }

    /// Closes the log with `closing` (the line not yet ended, ended, and the rate the lines arrived at).
    pub fn finish(mut self, closing: &str) -> std::io::Result<()> {
        self.log.write_all(closing.as_bytes())?;
        self.log.flush()
    }
}

// NOTE: every future here is ready when first polled: the port blocks, as the command line wants.
impl StreamPort for LiveStream<'_> {
    type Error = std::io::Error;

    async fn read(&mut self, buffer: &mut [u8]) -> std::io::Result<usize> {
        self.port.set_read_timeout(READ_WAIT)?;
        let count = match self.port.read(buffer) {
            Ok(count) => count,
            // NOTE: Ctrl-C interrupts the read: the run sees it in its flag, not as a port gone.
            Err(e) if matches!(e.kind(), ErrorKind::TimedOut | ErrorKind::WouldBlock | ErrorKind::Interrupted) => 0,
            Err(e) => return Err(e),
        };
        self.log.write_all(&buffer[..count])?;
        Ok(count)
    }

    fn now_s(&self) -> f64 {
        self.start.elapsed().as_secs_f64()
    }

    fn interrupted(&self) -> bool {
        self.interrupt.load(Ordering::SeqCst)
    }
}
