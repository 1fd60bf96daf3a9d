//! The link to a device: byte transports, the protocol client with one typed method per request,
//! opening a serial port, and finding accelcal boards among the serial ports (by USB ids, or by
//! their handshake after listening first).

mod client;
mod connect;
mod discovery;
pub mod port;
mod probe;

pub use accelcal_core::link::{
    describe, explain, holds_accelcal_frame, ChipOrtho9, Link, LinkError, StreamRequest, Tally, Transport,
};
pub use client::{Client, PortTransport};
pub use connect::{listen, open_listening, open_port, Connection, Opened as PortOpened, TalkingPort};
pub use discovery::{resolve_port, serial_ports, SerialPortEntry};
pub use port::{open_serial, pipe, PipeEnd, Port};
pub use probe::{ask, find_board, find_boards, is_worth_asking, Answer};
