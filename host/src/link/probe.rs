//! Finding accelcal boards whose USB identity is not accelcal's: the ESP32-C3 serves the host on its
//! own USB-Serial-JTAG, whose ids are Espressif's and fixed. Such a port is asked as
//! [`open_listening`] asks any port: listened to first, greeted only when it stayed silent; an
//! accelcal board answers the hello.

use super::connect::{open_listening, open_port, Connection, Opened};
use super::describe;
use super::discovery::SerialPortEntry;
use super::port::DEFAULT_BAUD;
use super::LinkError;

/// What a port that matches no accelcal id turned out to be.
pub enum Answer {
    /// An accelcal board: it stayed silent and answered the hello; the session is open.
    Board(Box<Connection>),
    /// It printed on its own while listened to (what, in words): nothing was written to it.
    Talks(String),
    /// No accelcal board: it could not be opened, or it stayed silent and did not answer the hello.
    NoBoard(LinkError),
}

impl Answer {
    /// What `accelcal ports` shows after the port: the board found by its handshake, or what it is not.
    pub fn shown(&self) -> String {
        match self {
            Answer::Board(connection) => format!(
                "  <- accelcal board (found by its handshake), board serial {}",
                String::from_utf8_lossy(&connection.info.serial.hex())
            ),
            Answer::Talks(heard) => format!("  (prints on its own: {heard}; nothing was written to it)"),
            Answer::NoBoard(LinkError::Silent { .. }) => {
                "  (no accelcal board: silent, and no answer to its hello)".into()
            }
            Answer::NoBoard(error) => format!("  (not an accelcal board, or not reachable: {error})"),
        }
    }
}

/// Whether a port is asked: a USB serial port without accelcal's ids. A port that is no USB device
/// (a computer's own UART, with a modem or a console behind it) is never written to.
pub fn is_worth_asking(entry: &SerialPortEntry) -> bool {
    !entry.is_accelcal && entry.usb_ids.is_some()
}

/// Asks the port at `path`: listens first, then says hello when it stayed silent. (A USB serial
/// port ignores the baud rate.)
pub fn ask(path: &str) -> Answer {
    match open_listening(path, DEFAULT_BAUD) {
        Ok(Opened::Board(connection)) => Answer::Board(connection),
        Ok(Opened::Talking(talking)) => Answer::Talks(describe(&talking.heard, talking.heard.len())),
        Err(error) => Answer::NoBoard(error),
    }
}

/// The one accelcal board among `ports`, opened: the port with accelcal's USB ids, or, when no port
/// has them, the one USB serial port of another identity that answers the handshake. `asking` hears
/// of each port before it is asked (asking takes over a second).
pub fn find_board(
    ports: &[SerialPortEntry],
    asking: &mut dyn FnMut(&SerialPortEntry),
) -> Result<Connection, LinkError> {
    let by_ids: Vec<&str> = ports.iter().filter(|p| p.is_accelcal).map(|p| p.path.as_str()).collect();
    match by_ids.as_slice() {
        [one] => return open_port(one, DEFAULT_BAUD),
        [] => {}
        several => return Err(LinkError::SeveralBoards { paths: several.join(", ") }),
    }
    let mut found = Vec::new();
    let asked: Vec<&SerialPortEntry> = ports.iter().filter(|p| is_worth_asking(p)).collect();
    for entry in &asked {
        asking(entry);
        if let Answer::Board(connection) = ask(&entry.path) {
            found.push((entry.path.as_str(), connection));
        }
    }
    match found.len() {
        0 => Err(LinkError::NoBoardFound { asked: asked.len() }),
        1 => Ok(*found.swap_remove(0).1),
        _ => Err(LinkError::SeveralBoards { paths: found.iter().map(|(p, _)| *p).collect::<Vec<_>>().join(", ") }),
    }
}

/// The paths of every accelcal board among `ports`: those with accelcal's USB ids, and the USB serial
/// ports of another identity that answer the handshake (each closed again after it). `asking` hears
/// of each port before it is asked.
pub fn find_boards(
    ports: &[SerialPortEntry],
    asking: &mut dyn FnMut(&SerialPortEntry),
) -> Result<Vec<String>, LinkError> {
    let mut found: Vec<String> = ports.iter().filter(|p| p.is_accelcal).map(|p| p.path.clone()).collect();
    for entry in ports.iter().filter(|p| is_worth_asking(p)) {
        asking(entry);
        if let Answer::Board(_) = ask(&entry.path) {
            found.push(entry.path.clone());
        }
    }
    match found.is_empty() {
        true => Err(LinkError::NoBoardFound { asked: ports.iter().filter(|p| is_worth_asking(p)).count() }),
        false => Ok(found),
    }
}
