//! The serial ports, accelcal's own USB ids (`shared::protocol`) marked, and naming a board by its
//! serial number. A board with another USB identity is found by its handshake (`probe.rs`).

use shared::protocol::{USB_PID, USB_VID};

use super::LinkError;

/// A serial port, and whether an accelcal board is behind it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SerialPortEntry {
    /// The path to open.
    pub path: String,
    /// The port is a USB device with accelcal's vendor and product ids.
    pub is_accelcal: bool,
    /// The USB serial number string, when the port is a USB device that has one.
    pub serial: Option<String>,
    /// The USB vendor and product ids, when the port is a USB device.
    pub usb_ids: Option<(u16, u16)>,
}

/// Every serial port of this machine.
pub fn serial_ports() -> Result<Vec<SerialPortEntry>, LinkError> {
    let ports = serialport::available_ports().map_err(|e| LinkError::ListPorts { reason: e.to_string() })?;
    Ok(ports
        .into_iter()
        .map(|port| SerialPortEntry {
            is_accelcal: is_accelcal(&port),
            serial: usb_serial(&port),
            usb_ids: usb_ids(&port),
            path: port.port_name,
        })
        .collect())
}

/// The path to open for `--port NAME`: NAME itself when it is a path, else the port of the board
/// whose USB serial number it is (case aside), looked up in `ports`.
pub fn resolve_port(
    name: &str,
    ports: impl FnOnce() -> Result<Vec<SerialPortEntry>, LinkError>,
) -> Result<String, LinkError> {
    if is_path(name) {
        return Ok(name.to_owned());
    }
    let ports = ports()?;
    let matching = |entry: &&SerialPortEntry| entry.serial.as_deref().is_some_and(|s| s.eq_ignore_ascii_case(name));
    match ports.iter().find(matching) {
        Some(entry) => Ok(entry.path.clone()),
        None => Err(LinkError::NoSuchSerial { serial: name.to_owned(), found: found(&ports) }),
    }
}

/// Whether `--port` names a path (Unix device files, Windows COM ports) rather than a serial number.
fn is_path(name: &str) -> bool {
    name.contains('/') || name.contains('\\') || name.to_ascii_uppercase().starts_with("COM")
}

/// The serial numbers found, for the message when none matches.
fn found(ports: &[SerialPortEntry]) -> String {
    let serials: Vec<String> =
        ports.iter().filter_map(|p| p.serial.as_ref().map(|s| format!("{s} on {}", p.path))).collect();
    if serials.is_empty() {
        "no port with a USB serial number was found".to_owned()
    } else {
        format!("found {}", serials.join(", "))
    }
}

fn usb_serial(port: &serialport::SerialPortInfo) -> Option<String> {
    match &port.port_type {
        serialport::SerialPortType::UsbPort(usb) => usb.serial_number.clone(),
        _ => None,
    }
}

fn usb_ids(port: &serialport::SerialPortInfo) -> Option<(u16, u16)> {
    match &port.port_type {
        serialport::SerialPortType::UsbPort(usb) => Some((usb.vid, usb.pid)),
        _ => None,
    }
}

fn is_accelcal(port: &serialport::SerialPortInfo) -> bool {
    usb_ids(port) == Some((USB_VID, USB_PID))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn entry(path: &str, serial: Option<&str>) -> SerialPortEntry {
        let usb_ids = serial.map(|_| (USB_VID, USB_PID));
        SerialPortEntry { path: path.into(), is_accelcal: serial.is_some(), serial: serial.map(str::to_owned), usb_ids }
    }

    fn listed() -> Result<Vec<SerialPortEntry>, LinkError> {
        Ok(vec![
            entry("/dev/ttyS0", None),
            entry("/dev/ttyACM0", Some("3A0027001551")),
            entry("/dev/ttyACM1", Some("1F00AB")),
        ])
    }

    #[test]
    fn a_board_is_found_by_its_serial_and_a_path_is_taken_as_it_is() {
        assert_eq!(resolve_port("3a0027001551", listed).unwrap(), "/dev/ttyACM0");
        assert_eq!(resolve_port("1F00AB", listed).unwrap(), "/dev/ttyACM1");
        let never = || -> Result<Vec<SerialPortEntry>, LinkError> { panic!("a path needs no port list") };
        assert_eq!(resolve_port("/dev/pts/3", never).unwrap(), "/dev/pts/3");
        assert_eq!(resolve_port("COM4", never).unwrap(), "COM4");
    }

    #[test]
    fn a_serial_that_matches_no_board_is_refused_naming_what_was_found() {
        let error = resolve_port("3A00", listed).unwrap_err().to_string();
        assert_eq!(
            error,
            "no serial port has the serial number 3A00 (found 3A0027001551 on /dev/ttyACM0, 1F00AB on /dev/ttyACM1): \
             give the serial number `accelcal ports` shows, or the port's path"
        );
        let none = resolve_port("3A00", || Ok(vec![entry("/dev/ttyS0", None)])).unwrap_err().to_string();
        assert!(none.contains("(no port with a USB serial number was found)"), "{none}");
    }
}
