//! The host's end of the emulated board's USB serial port: a pseudo-terminal, a new one each time
//! the cable is plugged in, as a real board's port goes away with its cable.

use std::collections::VecDeque;
use std::io::{ErrorKind, Read, Write};
use std::time::Duration;

use serialport::{SerialPort, TTYPort};

use super::EmulatorError;

/// The pseudo-terminal while the cable is in, and what the device sent that the host has not read.
pub(super) struct HostPort {
    /// The master end this bridge reads and writes, and the slave end the host opens (kept open, as
    /// reads on a master with no open slave fail).
    pty: Option<(TTYPort, TTYPort)>,
    to_host: VecDeque<u8>,
}

impl HostPort {
    /// A port with its cable plugged in.
    pub(super) fn plugged() -> Result<Self, EmulatorError> {
        let mut port = HostPort { pty: None, to_host: VecDeque::new() };
        port.plug()?;
        Ok(port)
    }

    /// Plugs the cable in: a fresh pseudo-terminal.
    pub(super) fn plug(&mut self) -> Result<(), EmulatorError> {
        let (mut master, slave) = TTYPort::pair().map_err(|e| EmulatorError::Pty(e.to_string()))?;
        master.set_timeout(Duration::ZERO).map_err(|e| EmulatorError::Pty(e.to_string()))?;
        self.pty = Some((master, slave));
        Ok(())
    }

    /// Pulls the cable: the host's reads and writes on the port fail from now on.
    pub(super) fn pull(&mut self) {
        self.pty = None;
        self.to_host.clear();
    }

    /// The path the host opens, while the cable is in.
    pub(super) fn path(&self) -> Option<String> {
        self.pty.as_ref().and_then(|(_, slave)| slave.name())
    }

    /// What the host wrote since the last call (nothing while the cable is out).
    pub(super) fn from_host(&mut self) -> Vec<u8> {
        let mut bytes = Vec::new();
        let Some((master, _)) = self.pty.as_mut() else { return bytes };
        let mut buffer = [0u8; 4096];
        while let Ok(n @ 1..) = master.read(&mut buffer) {
            bytes.extend_from_slice(&buffer[..n]);
        }
        bytes
    }

    /// Queues what the device sent and writes as much as the host has room for.
    pub(super) fn to_host(&mut self, bytes: &[u8]) {
        if self.pty.is_some() {
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
