//! Connecting to a device: a serial port (the board, or `accelcal sim --pty`), or a simulated board
//! in this process.

use firmware::sim::SimFlash;
use shared::protocol::DeviceInfo;

use crate::client::Client;
use crate::error::Error;
use crate::port::{open_serial, pipe, Port};
use crate::sim::SimBoard;

/// A device to talk to, and the simulated board behind it when there is one.
pub struct Connection {
    /// The protocol client.
    pub client: Client<Box<dyn Port>>,
    /// What the device said when the session opened.
    pub info: DeviceInfo,
    /// The in-process simulated board, for `--sim`.
    pub sim: Option<SimBoard>,
}

/// Where the device is.
#[derive(Debug, Clone, PartialEq)]
pub enum Target {
    /// A serial port path.
    Port(String),
    /// A simulated board in this process, seeded.
    Simulated { seed: u64 },
}

/// Opens the device and says hello.
pub fn connect(target: &Target) -> Result<Connection, Error> {
    match target {
        Target::Port(path) => {
            let port = open_serial(path).map_err(|e| Error::Open { port: path.clone(), reason: e.to_string() })?;
            let (client, info) = Client::connect(Box::new(port) as Box<dyn Port>)?;
            Ok(Connection { client, info, sim: None })
        }
        Target::Simulated { seed } => {
            let (host_end, device_end) = pipe();
            let board = SimBoard::spawn(device_end, SimFlash::new(), *seed);
            let (client, info) = Client::connect(Box::new(host_end) as Box<dyn Port>)?;
            Ok(Connection { client, info, sim: Some(board) })
        }
    }
}
