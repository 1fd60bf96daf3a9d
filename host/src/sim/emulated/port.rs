//! The host's end of the emulated board's USB serial port: a pseudo-terminal, a new one each time
//! the cable is plugged in, as a real board's port goes away with its cable. Whether a program on
//! the host has the port open is read from the master end (no slave end open: it hangs up), so that
//! DTR can rise and fall with it as it does on a real board's port.

use std::collections::VecDeque;
use std::io::{ErrorKind, Read, Write};
use std::time::Duration;

use serialport::{SerialPort, TTYPort};

use super::EmulatorError;

/// The pseudo-terminal while the cable is in, and what the device sent that the host has not read.
pub(super) struct HostPort {
    /// The master end this bridge reads and writes, and the path of the slave end the host opens.
    pty: Option<(TTYPort, String)>,
    to_host: VecDeque<u8>,
    /// Whether a program on the host has the port open.
    open: bool,
}

impl HostPort {
    /// A port with its cable plugged in.
    pub(super) fn plugged() -> Result<Self, EmulatorError> {
        let mut port = HostPort { pty: None, to_host: VecDeque::new(), open: false };
        port.plug()?;
        Ok(port)
    }

    /// Plugs the cable in: a fresh pseudo-terminal.
    pub(super) fn plug(&mut self) -> Result<(), EmulatorError> {
        let (mut master, slave) = TTYPort::pair().map_err(|e| EmulatorError::Pty(e.to_string()))?;
        master.set_timeout(Duration::ZERO).map_err(|e| EmulatorError::Pty(e.to_string()))?;
        let path = slave.name().ok_or(EmulatorError::Pty("the pseudo-terminal has no name".into()))?;
        // NOTE: the slave end is closed here, so that the master hangs up until the host opens it.
        self.pty = Some((master, path));
        Ok(())
    }

    /// Pulls the cable: the host's reads and writes on the port fail from now on.
    pub(super) fn pull(&mut self) {
        self.pty = None;
        self.to_host.clear();
        self.open = false;
    }

    /// The path the host opens, while the cable is in.
    pub(super) fn path(&self) -> Option<String> {
        self.pty.as_ref().map(|(_, path)| path.clone())
    }

    /// What the host wrote since the last call (nothing while the cable is out), and whether a
    /// program has the port open now; what the device sent is dropped when the port closes, as the
    /// kernel drops a closed serial port's unread input.
    pub(super) fn take_written(&mut self) -> (Vec<u8>, bool) {
        let mut bytes = Vec::new();
        let Some((master, path)) = self.pty.as_mut() else { return (bytes, false) };
        let mut buffer = [0u8; 4096];
        let open = loop {
            match master.read(&mut buffer) {
                Ok(n @ 1..) => bytes.extend_from_slice(&buffer[..n]),
                Err(e) if matches!(e.kind(), ErrorKind::TimedOut | ErrorKind::WouldBlock) => break true,
                Err(e) if e.kind() == ErrorKind::Interrupted => {}
                _ => break false, // hung up: no program has the port open
            }
        };
        let was_open = std::mem::replace(&mut self.open, open);
        if was_open != open {
            // NOTE: a closed port keeps no unread input (the kernel empties a serial port's at its
            // last close): what the device sent to the last program is not read by the next.
            self.to_host.clear();
            if !open {
                discard_unread(path);
            }
        }
        (bytes, open)
    }

    /// Queues what the device sent and writes as much as the host has room for.
    pub(super) fn send(&mut self, bytes: &[u8]) {
        if self.open {
            self.to_host.extend(bytes);
        }
        self.flush();
    }

    /// Writes what waits for the host, as far as it takes it now.
    pub(super) fn flush(&mut self) {
        let Some((master, _)) = self.pty.as_mut() else { return };
        while !self.to_host.is_empty() {
            let (front, _) = self.to_host.as_slices();
            match master.write(front) {
                Ok(n @ 1..) => drop(self.to_host.drain(..n)),
                Err(e) if e.kind() == ErrorKind::Interrupted => {}
                _ => break,
            }
        }
    }
}

/// Empties what the bridge wrote that the last program on the port left unread: it waits in the
/// slave end's line discipline, out of the master's reach (a flush of the master does not empty
/// it), so the slave end is opened for a moment to flush it (not as a controlling terminal).
fn discard_unread(path: &str) {
    use std::os::fd::AsRawFd;
    use std::os::unix::fs::OpenOptionsExt;

    use nix::fcntl::OFlag;
    use nix::sys::termios::{tcflush, FlushArg};

    let flags = (OFlag::O_NOCTTY | OFlag::O_NONBLOCK).bits();
    if let Ok(slave) = std::fs::OpenOptions::new().read(true).write(true).custom_flags(flags).open(path) {
        let _ = tcflush(slave.as_raw_fd(), FlushArg::TCIFLUSH);
    }
}
