//! The real binary against a port that is not an accelcal board: one that chatters text.

mod common;

use std::io::Write;
use std::time::Duration;

use common::accelcal_within;

/// A pseudo-terminal whose other end prints NMEA sentences, as a GPS receiver does, until dropped.
struct ChattyPort {
    path: String,
    stop: std::sync::Arc<std::sync::atomic::AtomicBool>,
    /// Bytes written to the port by whatever opened it.
    written: std::sync::Arc<std::sync::atomic::AtomicUsize>,
    _slave: serialport::TTYPort,
}

impl ChattyPort {
    fn start() -> Self {
        use std::sync::atomic::{AtomicBool, Ordering};
        let (mut master, slave) = serialport::TTYPort::pair().unwrap();
        let path = serialport::SerialPort::name(&slave).unwrap();
        let stop = std::sync::Arc::new(AtomicBool::new(false));
        let running = stop.clone();
        let written = std::sync::Arc::new(std::sync::atomic::AtomicUsize::new(0));
        let counted = written.clone();
        std::thread::spawn(move || {
            let line = b"$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*47\r\n";
            while !running.load(Ordering::Relaxed) {
                let _ = master.write_all(line);
                let mut drained = [0u8; 256];
                let read = std::io::Read::read(&mut master, &mut drained).unwrap_or(0);
                counted.fetch_add(read, Ordering::Relaxed);
                std::thread::sleep(Duration::from_millis(20));
            }
        });
        ChattyPort { path, stop, written, _slave: slave }
    }
}

impl Drop for ChattyPort {
    fn drop(&mut self) {
        self.stop.store(true, std::sync::atomic::Ordering::Relaxed);
    }
}

/// NOTE: accelcal listens before it writes (issue 24): a port that talks on its own is named after
/// the 1.2 s of listening and never written to (a MicroPython board would take the probe's 0x03 as
/// Ctrl-C).
#[test]
fn a_port_printing_nmea_text_is_named_not_an_accelcal_board_within_3_s_and_never_written_to() {
    let port = ChattyPort::start();
    let (output, elapsed) = accelcal_within(&["info", "--port", &port.path], Duration::from_secs(15));
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert!(!output.status.success(), "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("is not an accelcal board"), "{stderr}");
    assert!(stderr.contains("text such as \"$GPGGA,"), "{stderr}");
    assert!(stderr.contains("wrote nothing to it"), "{stderr}");
    assert!(stderr.contains("`accelcal ports`"), "{stderr}");
    std::thread::sleep(Duration::from_millis(100));
    assert_eq!(port.written.load(std::sync::atomic::Ordering::Relaxed), 0, "bytes were written to the port");
    // NOTE: 1.2 s of listening, plus process start-up.
    assert!(elapsed < Duration::from_secs(3), "took {elapsed:?}");
}

#[test]
fn a_port_held_by_another_program_is_named_busy_with_how_to_find_the_program() {
    let (_master, slave) = serialport::TTYPort::pair().unwrap();
    let path = serialport::SerialPort::name(&slave).unwrap();
    // Another program holds the port as accelcal does: exclusively (TIOCEXCL and flock).
    let _held = serialport::new(&path, 115_200).open().unwrap();
    let (output, _) = accelcal_within(&["info", "--port", &path], Duration::from_secs(10));
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert!(!output.status.success(), "{stderr}");
    assert_eq!(
        stderr.trim_end(),
        format!(
            "accelcal: {path} is in use by another program (a serial terminal, a monitor, ModemManager, another \
             accelcal): close it and run the command again; `fuser -v {path}` or `lsof {path}` names it"
        )
    );
}
