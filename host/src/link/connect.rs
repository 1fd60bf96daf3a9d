//! Opening a device on a serial port (the board, or `accelcal sim --pty`) and saying hello.

use shared::protocol::DeviceInfo;

use super::client::Client;
use super::error::LinkError;
use super::port::{open_serial, Port};

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

/// Opens the serial port at `path` and says hello.
pub fn open_port(path: &str) -> Result<Connection, LinkError> {
    let port = open_serial(path).map_err(|e| LinkError::opening(path, e))?;
    Connection::over(Box::new(port))
}
