//! Finding accelcal boards among the serial ports, by the USB ids of `shared::protocol`.

use shared::protocol::{USB_PID, USB_VID};

use super::error::LinkError;

/// A serial port, and whether an accelcal board is behind it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SerialPortEntry {
    /// The path to open.
    pub path: String,
    /// The port is a USB device with accelcal's vendor and product ids.
    pub is_accelcal: bool,
}

/// Every serial port of this machine.
pub fn serial_ports() -> Result<Vec<SerialPortEntry>, LinkError> {
    let ports = serialport::available_ports().map_err(|e| LinkError::ListPorts { reason: e.to_string() })?;
    Ok(ports
        .into_iter()
        .map(|port| SerialPortEntry { is_accelcal: is_accelcal(&port), path: port.port_name })
        .collect())
}

fn is_accelcal(port: &serialport::SerialPortInfo) -> bool {
    matches!(&port.port_type, serialport::SerialPortType::UsbPort(usb) if usb.vid == USB_VID && usb.pid == USB_PID)
}
