//! The link to a device: byte transports, the protocol client with one typed method per request,
//! opening a serial port, and finding accelcal boards among the serial ports (by USB ids, or by
//! their handshake after listening first).

mod client;
mod connect;
mod discovery;
pub mod port;
mod probe;
mod requests;
mod tally;

pub use accelcal_core::link::{describe, explain, holds_accelcal_frame, LinkError};
pub use client::Client;
pub use connect::{listen, open_listening, open_port, Connection, Opened as PortOpened, TalkingPort};
pub use discovery::{resolve_port, serial_ports, SerialPortEntry};
pub use port::{open_serial, pipe, PipeEnd, Port};
pub use probe::{ask, find_board, find_boards, is_worth_asking, Answer};
pub use requests::{ChipOrtho9, StreamRequest};
pub use tally::Tally;
