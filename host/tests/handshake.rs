//! Finding an accelcal board whose USB identity is not accelcal's (the ESP32-C3's USB-Serial-JTAG
//! has Espressif's fixed ids) by its handshake: the simulated board on a pseudo-terminal stands for
//! it, listed with Espressif's ids. A port that prints on its own is never written to; a silent
//! port that is no board gets accelcal's hello only after it was listened to.

mod common;

use std::io::Read;
use std::sync::atomic::Ordering;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use accelcal::limits::LISTEN_FIRST;
use accelcal::link::{
    ask, find_board, is_worth_asking, open_listening, open_port, Answer, LinkError, PortOpened, SerialPortEntry,
};
use accelcal::sim::replay::Replay;
use accelcal::sim::sketch::Sketch;
use common::SimPty;
use shared::protocol::{probe, PROTOCOL_VERSION};

/// The ESP32-C3's USB-Serial-JTAG ids (Espressif's vendor id, its fixed product id).
const ESPRESSIF_USB_SERIAL_JTAG: (u16, u16) = (0x303A, 0x1001);

fn listed_as_esp32c3(path: &str) -> SerialPortEntry {
    SerialPortEntry {
        path: path.to_owned(),
        is_accelcal: false,
        serial: Some("58:CF:79:E1:A2:B4".to_owned()),
        usb_ids: Some(ESPRESSIF_USB_SERIAL_JTAG),
    }
}

#[test]
fn a_board_with_espressifs_usb_ids_is_found_by_its_handshake() {
    let board = SimPty::start(&["--fast"]);
    let ports = [listed_as_esp32c3(&board.path)];
    assert!(is_worth_asking(&ports[0]));
    let mut asked = Vec::new();
    let found = find_board(&ports, &mut |entry| asked.push(entry.path.clone())).expect("the board answers its hello");
    assert_eq!(asked, std::slice::from_ref(&board.path), "the port is asked once, with progress");
    assert_eq!(found.info.protocol_version, PROTOCOL_VERSION);
    let serial = found.info.serial;
    drop(found);
    let direct = open_port(&board.path, 115_200).unwrap();
    assert_eq!(direct.info.serial, serial, "the board found is the one on that port");
}

#[test]
fn a_port_that_prints_on_its_own_is_named_and_never_written_to() {
    let sketch = Replay::spawn(Sketch::I2cdevlib, 3, 1.0).expect("a pseudo-terminal");
    let answer = ask(&sketch.path);
    assert!(matches!(&answer, Answer::Talks(heard) if heard.starts_with("text such as")), "not named as talking");
    let error = find_board(&[listed_as_esp32c3(&sketch.path)], &mut |_| {}).err().expect("no board there");
    assert!(matches!(error, LinkError::NoBoardFound { asked: 1 }), "{error}");
    assert_eq!(sketch.state.written.load(Ordering::SeqCst), 0, "bytes were written to a port that talks");
}

/// Issue 40: what accelcal writes to a silent port holds no byte a REPL or a bootloader acts on (the
/// old hello held 0x03 and 0x01, which stop a silent MicroPython program and enter its raw REPL).
#[test]
fn a_silent_port_that_is_no_board_is_greeted_only_after_it_was_listened_to_with_inert_bytes() {
    let (mut master, slave) = serialport::TTYPort::pair().unwrap();
    let path = serialport::SerialPort::name(&slave).unwrap();
    let first_byte_at: Arc<Mutex<Option<Instant>>> = Arc::default();
    let written: Arc<Mutex<Vec<u8>>> = Arc::default();
    let (seen, kept) = (first_byte_at.clone(), written.clone());
    std::thread::spawn(move || {
        let _ = serialport::SerialPort::set_timeout(&mut master, Duration::from_millis(50));
        let mut buffer = [0u8; 64];
        loop {
            if let Ok(n @ 1..) = master.read(&mut buffer) {
                seen.lock().unwrap().get_or_insert_with(Instant::now);
                kept.lock().unwrap().extend_from_slice(&buffer[..n]);
            }
        }
    });
    let asked_at = Instant::now();
    let answer = ask(&path);
    assert!(matches!(answer, Answer::NoBoard(LinkError::Silent { .. })), "a silent port is no board");
    let Answer::NoBoard(error) = answer else { unreachable!() };
    assert!(error.to_string().ends_with("run accelcal again once it prints"), "{error}");
    let first = first_byte_at.lock().unwrap().expect("the silent port was greeted");
    let listened = first - asked_at;
    assert!(listened >= LISTEN_FIRST, "written to after {listened:?}, before listening {LISTEN_FIRST:?}");
    let written = written.lock().unwrap().clone();
    assert!(written.len() >= 30 && written.ends_with(&[0]), "{written:02x?}");
    let acted_on: Vec<u8> = written.iter().copied().filter(|&b| b != 0 && !probe::is_inert(b)).collect();
    assert!(acted_on.is_empty(), "bytes a REPL or bootloader acts on: {acted_on:02x?} in {written:02x?}");
}

#[test]
fn a_port_that_is_no_usb_device_is_never_asked() {
    let board = SimPty::start(&["--fast"]);
    let uart = SerialPortEntry { path: board.path.clone(), is_accelcal: false, serial: None, usb_ids: None };
    assert!(!is_worth_asking(&uart));
    let error = find_board(&[uart], &mut |entry| panic!("{} was asked", entry.path)).err().unwrap();
    assert!(matches!(error, LinkError::NoBoardFound { asked: 0 }), "{error}");
}

#[test]
fn several_boards_and_none_are_refused_naming_the_way_out() {
    let none = find_board(&[], &mut |_| {}).err().unwrap().to_string();
    assert!(none.contains("no accelcal board found") && none.contains("--port"), "{none}");
    let ours = |path: &str| SerialPortEntry {
        path: path.into(),
        is_accelcal: true,
        serial: None,
        usb_ids: Some((0x1209, 0x0001)),
    };
    let several = find_board(&[ours("/dev/ttyACM0"), ours("/dev/ttyACM1")], &mut |_| panic!("nothing is asked"));
    let message = several.err().unwrap().to_string();
    assert!(message.contains("/dev/ttyACM0, /dev/ttyACM1") && message.contains("--port"), "{message}");
}

/// A sketch that begins to print only once something reaches the port: an Arduino that the port's
/// opening resets boots for 1-2 s, longer than accelcal listens, so its first line follows the hello.
fn sketch_printing_after_the_first_byte() -> String {
    use std::io::Write;
    let (mut master, slave) = serialport::TTYPort::pair().unwrap();
    let path = serialport::SerialPort::name(&slave).unwrap();
    std::thread::spawn(move || {
        let _slave = slave;
        let _ = serialport::SerialPort::set_timeout(&mut master, Duration::from_secs(30));
        let mut buffer = [0u8; 64];
        while !matches!(master.read(&mut buffer), Ok(n) if n > 0) {}
        for millis in (0..).step_by(10) {
            if master.write_all(format!("{millis},631,-106,15393,-158,108,59\r\n").as_bytes()).is_err() {
                return;
            }
            std::thread::sleep(Duration::from_millis(10));
        }
    });
    path
}

#[test]
fn a_sketch_that_starts_printing_after_the_hello_is_taken_as_talking_and_said_so() {
    let path = sketch_printing_after_the_first_byte();
    let Ok(PortOpened::Talking(talking)) = open_listening(&path, 115_200) else { panic!("not taken as talking") };
    assert!(talking.greeted, "the hello went before its first line");
    let heard = String::from_utf8_lossy(&talking.heard).into_owned();
    assert!(heard.contains(",631,-106,15393,-158,108,59\r\n"), "{heard:?}");
    let refused = open_port(&sketch_printing_after_the_first_byte(), 115_200).err().expect("no board there");
    assert!(matches!(refused, LinkError::TalksOnItsOwn { greeted: true, .. }), "{refused}");
    assert!(refused.to_string().contains("though it began only after accelcal's hello"), "{refused}");
}

#[test]
fn a_board_still_streaming_for_a_run_cut_short_is_greeted_as_a_board_and_left_idle() {
    use shared::protocol::{encode, Request, StreamKind, MAX_FRAME_LEN};
    use std::io::Write;
    let board = SimPty::start(&[]);
    // An earlier run asked for a long stream and ended (Ctrl-C, a kill) before reading its frames.
    let mut earlier = accelcal::link::open_serial(&board.path, 115_200).unwrap();
    let mut frame = [0u8; MAX_FRAME_LEN];
    let len =
        encode(1, &Request::Stream { kind: StreamKind::Raw, rate_hz: 100, count: 1_000_000 }, &mut frame).unwrap();
    earlier.write_all(&[[0u8].as_slice(), &frame[..len]].concat()).unwrap();
    std::thread::sleep(Duration::from_millis(300));
    drop(earlier);
    let opened = open_listening(&board.path, 115_200).unwrap();
    let PortOpened::Board(mut connection) = opened else {
        panic!("the board's leftover frames were taken for a sketch's stream");
    };
    // The stream was cancelled: the board takes a capture instead of answering busy.
    let seconds = shared::protocol::MIN_CAPTURE_SECONDS;
    let (stats, _) = connection.client.capture(seconds, |_| {}).expect("the board is idle again");
    let rate_hz = connection.info.config.sample_rate_hz;
    let wanted = u32::from(seconds) * u32::from(rate_hz);
    assert!(stats.samples + 2 >= wanted, "{} samples in {seconds} s at {rate_hz} Hz", stats.samples);
}
