//! The serve loop on a port and clock of the test's own, and the board helpers.

use embassy_futures::block_on;
use embedded_io_async::{ErrorKind, ErrorType, Read, Write};
use shared::protocol::{decode, encode, Request, Response, MAX_FRAME_LEN, PROTOCOL_VERSION};

use super::{led_lit, serial_number, serve_once, Clock};
use crate::device::Device;
use crate::server::Server;
use crate::sim::{sim_serial_number, SimFlash, SimMpu6050, SIM_FLASH_RANGE};

/// A port that hands out `incoming` (then waits for ever, as a quiet host) and keeps what is written.
#[derive(Default)]
struct Port {
    incoming: Vec<u8>,
    unplugged: bool,
    written: Vec<u8>,
    flushes: usize,
}

impl ErrorType for Port {
    type Error = ErrorKind;
}

impl Read for Port {
    async fn read(&mut self, buf: &mut [u8]) -> Result<usize, ErrorKind> {
        if self.unplugged {
            return Err(ErrorKind::NotConnected);
        }
        if self.incoming.is_empty() {
            core::future::pending::<()>().await;
        }
        let n = buf.len().min(self.incoming.len());
        buf[..n].copy_from_slice(&self.incoming[..n]);
        self.incoming.drain(..n);
        Ok(n)
    }
}

impl Write for Port {
    async fn write(&mut self, buf: &[u8]) -> Result<usize, ErrorKind> {
        let n = buf.len().min(7); // short writes: the loop must write the rest itself
        self.written.extend_from_slice(&buf[..n]);
        Ok(n)
    }

    async fn flush(&mut self) -> Result<(), ErrorKind> {
        self.flushes += 1;
        Ok(())
    }
}

/// A clock whose waits end at once and count the time they stand for.
#[derive(Default)]
struct Clock10 {
    now_ms: u64,
    waits: u32,
}

impl Clock for Clock10 {
    fn now_ms(&self) -> u64 {
        self.now_ms
    }

    async fn wait_ms(&mut self, ms: u64) {
        self.now_ms += ms;
        self.waits += 1;
    }
}

fn server() -> Server<SimMpu6050, SimFlash> {
    let device = Device::boot(SimMpu6050::new(4), SimFlash::new(), SIM_FLASH_RANGE, sim_serial_number(4));
    Server::new(block_on(device).unwrap())
}

#[test]
fn a_request_read_from_the_port_is_answered_in_one_whole_frame_then_flushed() {
    let mut frame = [0u8; MAX_FRAME_LEN];
    let len = encode(9, &Request::Hello { protocol_version: PROTOCOL_VERSION }, &mut frame).unwrap();
    let mut port = Port { incoming: frame[..len].to_vec(), ..Port::default() };
    let (mut server, mut clock) = (server(), Clock10::default());
    let had_error = block_on(serve_once(&mut server, &mut port, &mut clock));
    assert!(!had_error);
    assert_eq!((port.flushes, port.written.last()), (1, Some(&0)), "one frame, delimiter last");
    let mut body = port.written[..port.written.len() - 1].to_vec();
    let (id, response) = decode::<Response>(&mut body).unwrap();
    assert_eq!(id, 9);
    assert!(matches!(response, Response::Hello(info) if info.serial == sim_serial_number(4)));
}

#[test]
fn a_garbled_frame_is_answered_with_an_error_the_led_then_shows() {
    let mut port = Port { incoming: vec![0x13, 0x37, 0x00], ..Port::default() };
    let (mut server, mut clock) = (server(), Clock10::default());
    assert!(block_on(serve_once(&mut server, &mut port, &mut clock)), "the error answer is flagged");
    assert_eq!(port.flushes, 1);
}

#[test]
fn with_no_host_the_loop_waits_a_poll_period_and_writes_nothing() {
    let mut port = Port { unplugged: true, ..Port::default() };
    let (mut server, mut clock) = (server(), Clock10::default());
    assert!(!block_on(serve_once(&mut server, &mut port, &mut clock)));
    assert_eq!((clock.now_ms, port.written.len()), (super::POLL_PERIOD_MS, 0));
}

#[test]
fn a_quiet_port_lets_the_poll_period_pass_and_polls() {
    let mut port = Port::default();
    let (mut server, mut clock) = (server(), Clock10::default());
    assert!(!block_on(serve_once(&mut server, &mut port, &mut clock)));
    assert_eq!((clock.waits, port.flushes), (1, 0));
}

#[test]
fn the_led_beats_slowly_when_idle_stays_lit_when_busy_and_flashes_after_an_error() {
    let lit_ms = |busy, error: Option<u64>| (0..1000).filter(|&t| led_lit(10_000 + t, busy, error)).count();
    assert_eq!(lit_ms(false, None), 100, "idle: 100 ms a second");
    assert_eq!(lit_ms(true, None), 1000, "busy: steady");
    assert_eq!(lit_ms(false, Some(9_500)), 500, "after an error: 100 ms on, 100 ms off");
    assert_eq!(lit_ms(true, Some(10_000 - super::ERROR_SHOWN_FOR_MS)), 1000, "the error shown for 3 s only");
}

#[test]
fn a_short_unique_id_is_padded_in_front_and_a_long_one_keeps_its_last_bytes() {
    assert_eq!(serial_number(&[0xAB, 0xCD]).0, [0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0xAB, 0xCD]);
    let long: Vec<u8> = (1..=16).collect();
    assert_eq!(serial_number(&long).0.to_vec(), (5..=16).collect::<Vec<u8>>());
}
