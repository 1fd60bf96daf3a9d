//! The protocol client: requests out, responses in, over any [`Port`], never waiting forever.

use std::collections::VecDeque;
use std::io::{self, ErrorKind};
use std::time::{Duration, Instant};

use shared::protocol::{self, DeviceInfo, Feed, FrameAccumulator, Request, Response, MAX_FRAME_LEN, PROTOCOL_VERSION};

use crate::error::Error;
use crate::port::Port;

/// Longest silence from a device before it is declared gone.
pub const SILENCE_LIMIT: Duration = Duration::from_secs(2);
/// How long one read waits, so that silence is noticed promptly.
const READ_SLICE: Duration = Duration::from_millis(50);

/// A connection to one device.
pub struct Client<P: Port> {
    port: P,
    accumulator: FrameAccumulator,
    decoded: VecDeque<Result<(u16, Response), Error>>,
    next_id: u16,
}

impl<P: Port> Client<P> {
    /// Opens a session: says hello and checks the protocol version.
    pub fn connect(mut port: P) -> Result<(Self, DeviceInfo), Error> {
        port.set_read_timeout(READ_SLICE).map_err(|e| Error::io("setting the read timeout", e))?;
        let mut client = Client { port, accumulator: FrameAccumulator::new(), decoded: VecDeque::new(), next_id: 1 };
        // A leading delimiter ends any half frame left in the device's buffer by an earlier session.
        client.port.write_all(&[0]).map_err(disconnected)?;
        match client.call(Request::Hello { protocol_version: PROTOCOL_VERSION })? {
            Response::Hello(info) if info.protocol_version == PROTOCOL_VERSION => Ok((client, info)),
            Response::Hello(info) => Err(Error::Version { device: info.protocol_version, host: PROTOCOL_VERSION }),
            other => Err(unexpected(&other)),
        }
    }

    /// A request that completes at once: its final response; a device error becomes `Err`.
    pub fn call(&mut self, request: Request) -> Result<Response, Error> {
        self.run(request, |_| {})
    }

    /// A request with progress (capture) or samples (stream): each goes to `on_update`; returns the
    /// final response. Fails when the device is silent for [`SILENCE_LIMIT`].
    pub fn run(&mut self, request: Request, mut on_update: impl FnMut(&Response)) -> Result<Response, Error> {
        let id = self.send(&request)?;
        let mut last_heard = Instant::now();
        let mut updates = 0usize;
        loop {
            let message = match self.receive(&mut last_heard) {
                // Silence after progress: the device was there and no longer is.
                Err(Error::Silent { .. }) if updates > 0 => return Err(Error::StoppedAnswering),
                other => other?,
            };
            match message {
                (answer_id, _) if answer_id != id && answer_id != protocol::frame::UNKNOWN_REQUEST_ID => {}
                (_, Response::Error(error)) => return Err(error.into()),
                (_, update @ (Response::Progress(_) | Response::Sample(_))) => {
                    updates += 1;
                    on_update(&update)
                }
                (_, last) => return Ok(last),
            }
        }
    }

    /// Asks the device to stop its capture or stream (the running `run` then ends).
    pub fn cancel(&mut self) -> Result<(), Error> {
        self.send(&Request::Cancel).map(|_| ())
    }

    fn send(&mut self, request: &Request) -> Result<u16, Error> {
        let id = self.next_id;
        // NOTE: id 0 is reserved for answers to unreadable frames.
        self.next_id = self.next_id.checked_add(1).unwrap_or(1);
        let mut frame = [0u8; MAX_FRAME_LEN];
        let len = protocol::encode(id, request, &mut frame).map_err(|e| Error::Protocol(format!("{e:?}")))?;
        self.port.write_all(&frame[..len]).map_err(disconnected)?;
        self.port.flush().map_err(disconnected)?;
        Ok(id)
    }

    /// The next decodable response: from those already read, else from the port.
    fn receive(&mut self, last_heard: &mut Instant) -> Result<(u16, Response), Error> {
        let mut buffer = [0u8; 256];
        loop {
            if let Some(message) = self.decoded.pop_front() {
                return message;
            }
            let n = match self.port.read(&mut buffer) {
                Ok(0) => return Err(Error::Disconnected { reason: "end of stream".into() }),
                Ok(n) => n,
                Err(e) if matches!(e.kind(), ErrorKind::TimedOut | ErrorKind::WouldBlock | ErrorKind::Interrupted) => {
                    if last_heard.elapsed() > SILENCE_LIMIT {
                        return Err(Error::Silent { seconds: SILENCE_LIMIT.as_secs_f64() });
                    }
                    continue;
                }
                Err(e) => return Err(disconnected(e)),
            };
            *last_heard = Instant::now();
            for &byte in &buffer[..n] {
                let Feed::Frame(frame) = self.accumulator.feed(byte) else { continue };
                match protocol::decode::<Response>(frame) {
                    Ok(message) => self.decoded.push_back(Ok(message)),
                    Err(protocol::FrameError::Version { got }) => {
                        self.decoded.push_back(Err(Error::Version { device: got, host: PROTOCOL_VERSION }))
                    }
                    // A corrupted frame: its request is answered by nothing, and times out.
                    Err(_) => {}
                }
            }
        }
    }
}

fn disconnected(error: io::Error) -> Error {
    Error::Disconnected { reason: error.to_string() }
}

fn unexpected(response: &Response) -> Error {
    Error::Protocol(format!("{response:?}"))
}
