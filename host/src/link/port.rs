//! Byte transports to a device: the serial port (real board or pseudo-terminal) and an in-memory
//! pipe to the in-process simulated board. The protocol client and the simulated board take any of
//! them.

use std::io::{self, Read, Write};
use std::sync::mpsc::{channel, Receiver, RecvTimeoutError, Sender};
use std::time::Duration;

use serialport::SerialPort;

/// A duplex byte stream whose reads give up after a settable time with `ErrorKind::TimedOut`.
pub trait Port: Read + Write + Send {
    /// How long a read waits for the first byte.
    fn set_read_timeout(&mut self, timeout: Duration) -> io::Result<()>;
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
}

impl Port for serialport::TTYPort {
    fn set_read_timeout(&mut self, timeout: Duration) -> io::Result<()> {
        SerialPort::set_timeout(self, timeout).map_err(io::Error::from)
    }
}

/// Baud rate of the serial port. NOTE: USB CDC ignores it; it matters only to UART bridges.
const BAUD: u32 = 115_200;

/// Opens a serial port (the board, or a pseudo-terminal of `accelcal sim --pty`).
pub fn open_serial(path: &str) -> Result<Box<dyn SerialPort>, serialport::Error> {
    serialport::new(path, BAUD).timeout(Duration::from_millis(100)).open()
}

/// One end of an in-memory duplex pipe.
#[derive(Debug)]
pub struct PipeEnd {
    incoming: Receiver<Vec<u8>>,
    outgoing: Sender<Vec<u8>>,
    pending: Vec<u8>,
    timeout: Duration,
}

/// Two connected pipe ends: what one writes, the other reads.
pub fn pipe() -> (PipeEnd, PipeEnd) {
    let (a_to_b, b_from_a) = channel();
    let (b_to_a, a_from_b) = channel();
    let end =
        |incoming, outgoing| PipeEnd { incoming, outgoing, pending: Vec::new(), timeout: Duration::from_millis(100) };
    (end(a_from_b, a_to_b), end(b_from_a, b_to_a))
}

impl Read for PipeEnd {
    fn read(&mut self, buffer: &mut [u8]) -> io::Result<usize> {
        if self.pending.is_empty() {
            self.pending = match self.incoming.recv_timeout(self.timeout) {
                Ok(bytes) => bytes,
                Err(RecvTimeoutError::Timeout) => return Err(io::ErrorKind::TimedOut.into()),
                Err(RecvTimeoutError::Disconnected) => return Err(io::ErrorKind::BrokenPipe.into()),
            };
        }
        let n = buffer.len().min(self.pending.len());
        buffer[..n].copy_from_slice(&self.pending[..n]);
        self.pending.drain(..n);
        Ok(n)
    }
}

impl Write for PipeEnd {
    fn write(&mut self, bytes: &[u8]) -> io::Result<usize> {
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
}
