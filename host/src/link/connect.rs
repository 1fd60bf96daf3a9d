//! Opening a device on a serial port (the board, or `accelcal sim --pty`) and saying hello, after
//! listening first: accelcal's firmware speaks only when asked, so a port that talks on its own is a
//! board running someone's own sketch, and nothing is written to it (on a MicroPython board the
//! probe's 0x03 would stop the program).

use std::io::Read;
use std::time::{Duration, Instant};

use shared::protocol::{DeviceInfo, Request};

use super::client::Client;
use super::port::{open_serial, Port};
use super::{describe, holds_accelcal_frame, LinkError};
use crate::limits::LISTEN_FIRST;

/// An open session with a device.
pub struct Connection {
    /// The protocol client.
    pub client: Client<Box<dyn Port>>,
    /// What the device said when the session opened.
    pub info: DeviceInfo,
}

impl Connection {
    /// Says hello over any port.
    pub fn over(port: Box<dyn Port>) -> Result<Self, LinkError> {
        let (client, info) = Client::connect(port)?;
        Ok(Connection { client, info })
    }
}

/// A port that talked on its own, never written to.
pub struct TalkingPort {
    /// Its path.
    pub path: String,
    /// The open port.
    pub port: Box<dyn Port>,
    /// What it said while accelcal listened.
    pub heard: Vec<u8>,
    /// It began to talk only after accelcal's hello was written to it (a board the port's opening
    /// reset, a sketch slow to start).
    pub greeted: bool,
}

/// What is behind a port.
pub enum Opened {
    /// An accelcal board, greeted.
    Board(Box<Connection>),
    /// A board that prints on its own.
    Talking(TalkingPort),
}

/// Opens the serial port at `path` at `baud`, listens, and says hello only when it stayed silent.
pub fn open_listening(path: &str, baud: u32) -> Result<Opened, LinkError> {
    let port = open_serial(path, baud).map_err(|e| not_opened(path, e))?;
    let mut port: Box<dyn Port> = Box::new(port);
    let heard = listen(&mut port, LISTEN_FIRST)?;
    // NOTE: frames of our own protocol are an accelcal board still ending what an earlier run, cut
    // short, asked of it: greeted, and its job cancelled, never taken for a sketch's stream.
    let leftovers = holds_accelcal_frame(&heard);
    if !heard.is_empty() && !leftovers {
        return Ok(Opened::Talking(TalkingPort { path: path.to_owned(), port, heard, greeted: false }));
    }
    match Client::connect_keeping(port) {
        Ok((mut client, info)) if leftovers => {
            client.call(Request::Cancel)?;
            Ok(Opened::Board(Box::new(Connection { client, info })))
        }
        Ok((client, info)) => Ok(Opened::Board(Box::new(Connection { client, info }))),
        Err((LinkError::NotAccelcal { seconds, seen }, port)) => started_late(path, port, seconds, seen),
        Err((LinkError::Silent { seconds, .. }, _)) => Err(LinkError::Silent { seconds, at_open: true }),
        Err((error, _)) => Err(error),
    }
}

/// A port that was silent while listened to and began to print after accelcal's hello (an Arduino
/// that the port's opening reset boots for 1-2 s): listened to again and taken as talking, unless it
/// has fallen silent again.
fn started_late(path: &str, mut port: Box<dyn Port>, seconds: f64, seen: String) -> Result<Opened, LinkError> {
    let heard = listen(&mut port, LISTEN_FIRST)?;
    if heard.is_empty() {
        return Err(LinkError::NotAccelcal { seconds, seen });
    }
    Ok(Opened::Talking(TalkingPort { path: path.to_owned(), port, heard, greeted: true }))
}

/// Opens the serial port at `path` at `baud` and says hello; a port that talks on its own is refused
/// unwritten.
pub fn open_port(path: &str, baud: u32) -> Result<Connection, LinkError> {
    match open_listening(path, baud)? {
        Opened::Board(connection) => Ok(*connection),
        Opened::Talking(talking) => {
            let seen = describe(&talking.heard, talking.heard.len());
            Err(LinkError::TalksOnItsOwn { path: talking.path, seen, greeted: talking.greeted })
        }
    }
}

/// Every byte the port sends within `span`, without writing to it.
pub fn listen(port: &mut Box<dyn Port>, span: Duration) -> Result<Vec<u8>, LinkError> {
    let start = Instant::now();
    let mut heard = Vec::new();
    let mut buffer = [0u8; 512];
    while start.elapsed() < span {
        port.set_read_timeout(span.saturating_sub(start.elapsed()).max(Duration::from_millis(1)))
            .map_err(|e| LinkError::Disconnected { reason: e.to_string() })?;
        match port.read(&mut buffer) {
            Ok(0) => std::thread::sleep(Duration::from_millis(10)),
            Ok(n) => heard.extend_from_slice(&buffer[..n]),
            Err(e) if matches!(e.kind(), std::io::ErrorKind::TimedOut | std::io::ErrorKind::WouldBlock) => {}
            Err(e) => return Err(LinkError::Disconnected { reason: e.to_string() }),
        }
    }
    Ok(heard)
}

/// Why the serial port at `port` did not open.
fn not_opened(port: &str, error: serialport::Error) -> LinkError {
    // NOTE: serialport reports a port another program holds (open(2) failing with EBUSY under
    // its TIOCEXCL, or its exclusive flock taken) as NoDevice; a missing path is Io(NotFound).
    match error.kind() {
        serialport::ErrorKind::NoDevice => LinkError::PortBusy { port: port.to_owned() },
        _ => LinkError::Open { port: port.to_owned(), reason: error.to_string() },
    }
}
