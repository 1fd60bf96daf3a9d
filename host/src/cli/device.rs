//! Opening the device a command names: a serial port, or a simulated board in this process (with
//! the tool's own hand on it).

use super::args::Device;
use crate::error::Error;
use crate::limits::LISTEN_FIRST;
use crate::link::{
    find_board, open_listening, open_port, resolve_port, serial_ports, PortOpened, SerialPortEntry, TalkingPort,
};
use crate::opened::Opened;
use crate::sim::SimBoard;

impl Device {
    /// Opens the device, or, when its port talks on its own, hands the port over unwritten.
    pub(super) fn open_or_talking(&self) -> Result<Result<Opened, Box<TalkingPort>>, Error> {
        match &self.port {
            Some(name) => match open_listening(&resolve_port(name, serial_ports)?, self.baud)? {
                PortOpened::Board(connection) => Ok(Ok(Opened::new(*connection, None, self.seed))),
                PortOpened::Talking(talking) => Ok(Err(Box::new(talking))),
            },
            None => self.open().map(Ok),
        }
    }

    /// Opens the device and says hello.
    pub(super) fn open(&self) -> Result<Opened, Error> {
        match (&self.port, self.sim) {
            (Some(name), _) => {
                let connection = open_port(&resolve_port(name, serial_ports)?, self.baud)?;
                Ok(Opened::new(connection, None, self.seed))
            }
            (None, true) => {
                let part = self.sim_part.part(self.sim_faulty_axis);
                let (connection, board) =
                    SimBoard::in_process_part((self.seed, self.sim_sensor.unwrap_or_default(), part))?;
                Ok(Opened::new(connection, Some(board), self.seed))
            }
            (None, false) => {
                let connection = find_board(&serial_ports()?, &mut asking)?;
                Ok(Opened::new(connection, None, self.seed))
            }
        }
    }
}

/// The progress line before a port is asked (which takes over a second).
pub(super) fn asking(port: &SerialPortEntry) {
    let (vendor, product) = port.usb_ids.unwrap_or_default();
    eprintln!(
        "asking {} (USB {vendor:04x}:{product:04x}, not accelcal's ids): listening {:.1} s first, then accelcal's hello",
        port.path,
        LISTEN_FIRST.as_secs_f64()
    );
}
