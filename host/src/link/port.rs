//! Byte transports to a device: the serial port (real board or pseudo-terminal) and an in-memory
//! pipe to the in-process simulated board. The protocol client and the simulated board take any of
//! them.

use std::io::{self, Read, Write};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::mpsc::{channel, Receiver, RecvTimeoutError, Sender};
use std::sync::Arc;
use std::time::Duration;

use serialport::SerialPort;

/// A duplex byte stream whose reads give up after a settable time with `ErrorKind::TimedOut`.
pub trait Port: Read + Write + Send {
    /// How long a read waits for the first byte.
    fn set_read_timeout(&mut self, timeout: Duration) -> io::Result<()>;

    /// Whether the other end has read everything this end wrote, this end has read everything it
    /// wrote, and it now waits to read: it has acted on all it was sent. Only an in-memory pipe
    /// can tell; a simulated board in lockstep waits for it before letting time pass.
    fn peer_settled(&self) -> bool {
        true
    }
}

impl Port for dyn SerialPort {
    fn set_read_timeout(&mut self, timeout: Duration) -> io::Result<()> {
        self.set_timeout(timeout).map_err(io::Error::from)
    }
}

impl<P: Port + ?Sized> Port for Box<P> {
    fn set_read_timeout(&mut self, timeout: Duration) -> io::Result<()> {
        (**self).set_read_timeout(timeout)
    }

    fn peer_settled(&self) -> bool {
        (**self).peer_settled()
    }
}

impl Port for serialport::TTYPort {
    fn set_read_timeout(&mut self, timeout: Duration) -> io::Result<()> {
        SerialPort::set_timeout(self, timeout).map_err(io::Error::from)
    }
}

/// The baud rate a port opens at unless told otherwise (`--baud`): accelcal's firmware and most
/// sketches' `Serial.begin(115200)`. NOTE: USB CDC ignores it; it matters only to UART bridges.
pub const DEFAULT_BAUD: u32 = 115_200;

/// Opens a serial port (the board, or a pseudo-terminal of `accelcal sim --pty`) at `baud`.
pub fn open_serial(path: &str, baud: u32) -> Result<Box<dyn SerialPort>, serialport::Error> {
    serialport::new(path, baud).timeout(Duration::from_millis(100)).open()
}

/// One end of an in-memory duplex pipe.
#[derive(Debug)]
pub struct PipeEnd {
    incoming: Receiver<Vec<u8>>,
    outgoing: Sender<Vec<u8>>,
    pending: Vec<u8>,
    timeout: Duration,
    shared: Arc<PipeState>,
    side: usize,
}

/// What both ends of a pipe see: per end, the bytes written to it and not yet read, and whether it
/// is blocked waiting to read.
#[derive(Debug, Default)]
struct PipeState {
    unread: [AtomicUsize; 2],
    waiting: [AtomicBool; 2],
}

/// Two connected pipe ends: what one writes, the other reads.
pub fn pipe() -> (PipeEnd, PipeEnd) {
    let (a_to_b, b_from_a) = channel();
    let (b_to_a, a_from_b) = channel();
    let shared = Arc::new(PipeState::default());
    let end = |incoming, outgoing, side| PipeEnd {
        incoming,
        outgoing,
        pending: Vec::new(),
        timeout: Duration::from_millis(100),
        shared: shared.clone(),
        side,
    };
    (end(a_from_b, a_to_b, 0), end(b_from_a, b_to_a, 1))
}

impl Read for PipeEnd {
    fn read(&mut self, buffer: &mut [u8]) -> io::Result<usize> {
        if self.pending.is_empty() {
            self.shared.waiting[self.side].store(true, Ordering::SeqCst);
            let received = self.incoming.recv_timeout(self.timeout);
            self.shared.waiting[self.side].store(false, Ordering::SeqCst);
            self.pending = match received {
                Ok(bytes) => bytes,
                Err(RecvTimeoutError::Timeout) => return Err(io::ErrorKind::TimedOut.into()),
                Err(RecvTimeoutError::Disconnected) => return Err(io::ErrorKind::BrokenPipe.into()),
            };
        }
        let n = buffer.len().min(self.pending.len());
        buffer[..n].copy_from_slice(&self.pending[..n]);
        self.pending.drain(..n);
        self.shared.unread[self.side].fetch_sub(n, Ordering::SeqCst);
        Ok(n)
    }
}

impl Write for PipeEnd {
    fn write(&mut self, bytes: &[u8]) -> io::Result<usize> {
        self.shared.unread[1 - self.side].fetch_add(bytes.len(), Ordering::SeqCst);
        self.outgoing.send(bytes.to_vec()).map_err(|_| io::Error::from(io::ErrorKind::BrokenPipe))?;
        Ok(bytes.len())
    }

    fn flush(&mut self) -> io::Result<()> {
        Ok(())
    }
}

impl Port for PipeEnd {
    fn set_read_timeout(&mut self, timeout: Duration) -> io::Result<()> {
        self.timeout = timeout;
        Ok(())
    }

    fn peer_settled(&self) -> bool {
        let (own, peer) = (self.side, 1 - self.side);
        let state = &self.shared;
        state.unread[own].load(Ordering::SeqCst) == 0
            && state.unread[peer].load(Ordering::SeqCst) == 0
            && state.waiting[peer].load(Ordering::SeqCst)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pipe_carries_bytes_both_ways_and_times_out_when_silent() {
        let (mut a, mut b) = pipe();
        a.write_all(b"hello").unwrap();
        let mut buffer = [0u8; 3];
        assert_eq!(b.read(&mut buffer).unwrap(), 3);
        assert_eq!(&buffer, b"hel");
        assert_eq!(b.read(&mut buffer).unwrap(), 2);
        b.set_read_timeout(Duration::from_millis(5)).unwrap();
        assert_eq!(b.read(&mut buffer).unwrap_err().kind(), io::ErrorKind::TimedOut);
        drop(a);
        assert_eq!(b.read(&mut buffer).unwrap_err().kind(), io::ErrorKind::BrokenPipe);
    }

    #[test]
    fn a_serial_port_opens_at_the_baud_rate_it_is_given() {
        let (_master, slave) = serialport::TTYPort::pair().expect("a pseudo-terminal pair");
        let path = slave.name().expect("the pseudo-terminal has a path");
        for baud in [38_400, DEFAULT_BAUD] {
            let port = open_serial(&path, baud).expect("the pseudo-terminal opens");
            assert_eq!(port.baud_rate().expect("its baud rate reads back"), baud);
        }
    }
}
