//! The protocol client: requests out, responses in, over any [`Port`], never waiting forever.

use std::collections::VecDeque;
use std::io::ErrorKind;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Duration;

use shared::protocol::{self, DeviceInfo, Feed, FrameAccumulator, Request, Response, MAX_FRAME_LEN};

use super::error::LinkError;
use super::listening::Listening;
use super::port::Port;
use crate::limits::SILENCE_LIMIT;

/// How long one read waits, so that silence is noticed promptly.
const READ_SLICE: Duration = Duration::from_millis(50);

/// A connection to one device.
pub struct Client<P: Port> {
    port: P,
    accumulator: FrameAccumulator,
    decoded: VecDeque<Result<(u16, Response), LinkError>>,
    next_id: u16,
    interrupt: Option<Arc<AtomicBool>>,
}

impl<P: Port> Client<P> {
    /// Opens a session: says hello and checks the protocol version.
    pub fn connect(port: P) -> Result<(Self, DeviceInfo), LinkError> {
        Self::connect_keeping(port).map_err(|(error, _)| error)
    }

    /// Opens a session as [`Client::connect`] does; when that fails, the port comes back with the
    /// error, for a caller that goes on reading what the device prints.
    pub fn connect_keeping(mut port: P) -> Result<(Self, DeviceInfo), (LinkError, P)> {
        if let Err(error) = port.set_read_timeout(READ_SLICE) {
            return Err((LinkError::Timeout(error), port));
        }
        let mut client = Client {
            port,
            accumulator: FrameAccumulator::new(),
            decoded: VecDeque::new(),
            next_id: 1,
            interrupt: None,
        };
        // A leading delimiter ends any half frame left in the device's buffer by an earlier session.
        let said = client.port.write_all(&[0]).map_err(LinkError::disconnected);
        match said.and_then(|()| client.hello()) {
            Ok(info) => Ok((client, info)),
            Err(error) => Err((error, client.port)),
        }
    }

    /// Once `flag` is set (by Ctrl-C), the running capture or stream is cancelled on the device and
    /// every request ends with [`LinkError::Interrupted`].
    pub fn interrupt_on(&mut self, flag: Arc<AtomicBool>) {
        self.interrupt = Some(flag);
    }

    /// Takes the Ctrl-C flag away (until given again), for what must still be said to the device
    /// after an interruption (writing its configuration back).
    pub fn take_interrupt(&mut self) -> Option<Arc<AtomicBool>> {
        self.interrupt.take()
    }

    fn interrupted(&self) -> bool {
        self.interrupt.as_ref().is_some_and(|flag| flag.load(Ordering::SeqCst))
    }

    /// A request that completes at once: its final response; a device error becomes `Err`.
    pub fn call(&mut self, request: Request) -> Result<Response, LinkError> {
        self.run(request, |_| {})
    }

    /// A request with progress (capture) or samples (stream): each goes to `on_update`; returns the
    /// final response. Fails when the device is silent for [`SILENCE_LIMIT`].
    pub fn run(&mut self, request: Request, mut on_update: impl FnMut(&Response)) -> Result<Response, LinkError> {
        self.run_while(request, |update| {
            on_update(update);
            true
        })
    }

    /// As [`Client::run`]; once `on_update` returns `false` the device is asked to stop, and its
    /// final response is still awaited (a cancelled stream ends with what it sent).
    pub fn run_while(
        &mut self,
        request: Request,
        mut on_update: impl FnMut(&Response) -> bool,
    ) -> Result<Response, LinkError> {
        if self.interrupted() {
            return Err(LinkError::Interrupted);
        }
        let id = self.send(&request)?;
        let mut listening = Listening::new();
        let (mut updates, mut cancelled, mut interrupted) = (0usize, false, false);
        loop {
            if !interrupted && self.interrupted() {
                // NOTE: the device ends the cancelled operation with its final response, awaited below.
                self.cancel()?;
                (cancelled, interrupted) = (true, true);
            }
            let (answer_id, response) = match self.receive(&mut listening) {
                // Silence after progress: the device was there and no longer is.
                Err(LinkError::Silent { .. }) if updates > 0 => return Err(LinkError::StoppedAnswering),
                other => other?,
            };
            if !answers(id, answer_id) {
                continue;
            }
            match response {
                Response::Progress(_) | Response::Sample(_) => {
                    updates += 1;
                    if !on_update(&response) && !cancelled {
                        self.cancel()?;
                        cancelled = true;
                    }
                }
                _ if interrupted => return Err(LinkError::Interrupted),
                Response::Error(error) => return Err(error.into()),
                last => return Ok(last),
            }
        }
    }

    /// Asks the device to stop its capture or stream (the running `run` then ends).
    pub fn cancel(&mut self) -> Result<(), LinkError> {
        self.send(&Request::Cancel).map(|_| ())
    }

    fn send(&mut self, request: &Request) -> Result<u16, LinkError> {
        let id = self.next_id;
        // NOTE: id 0 is reserved for answers to unreadable frames.
        self.next_id = self.next_id.checked_add(1).unwrap_or(1);
        let mut frame = [0u8; MAX_FRAME_LEN];
        let len = protocol::encode(id, request, &mut frame)
            .map_err(|e| LinkError::Encode { request: request_name(request), reason: format!("{e:?}") })?;
        self.port.write_all(&frame[..len]).map_err(LinkError::disconnected)?;
        self.port.flush().map_err(LinkError::disconnected)?;
        Ok(id)
    }

    /// The next decodable response: from those already read, else from the port. Fails after
    /// [`SILENCE_LIMIT`] without a frame, however many other bytes arrive.
    fn receive(&mut self, listening: &mut Listening) -> Result<(u16, Response), LinkError> {
        let mut buffer = [0u8; 256];
        loop {
            if let Some(message) = self.decoded.pop_front() {
                listening.frame();
                return message;
            }
            match self.port.read(&mut buffer) {
                Ok(0) => return Err(LinkError::Disconnected { reason: "end of stream".into() }),
                Ok(n) => {
                    listening.bytes(&buffer[..n]);
                    self.decode(&buffer[..n]);
                }
                Err(e) if matches!(e.kind(), ErrorKind::TimedOut | ErrorKind::WouldBlock | ErrorKind::Interrupted) => {}
                Err(e) => return Err(LinkError::disconnected(e)),
            }
            // NOTE: a frame just read is taken before the silence is judged: a host that reads late
            // (busy, or descheduled on a loaded machine) finds the answer waiting, not a silent board.
            if self.decoded.is_empty() {
                listening.check(SILENCE_LIMIT)?;
            }
        }
    }

    /// Feeds bytes to the frame accumulator and queues every message they complete.
    fn decode(&mut self, bytes: &[u8]) {
        for &byte in bytes {
            let Feed::Frame(frame) = self.accumulator.feed(byte) else { continue };
            match protocol::decode::<Response>(frame) {
                Ok(message) => self.decoded.push_back(Ok(message)),
                Err(protocol::FrameError::Version { got }) => self.decoded.push_back(Err(LinkError::version(got))),
                // A corrupted frame: its request is answered by nothing, and times out.
                Err(_) => {}
            }
        }
    }
}

/// Whether a response with `answer_id` answers the request sent as `id`: its own id, or the id of
/// answers to frames the device could not read.
fn answers(id: u16, answer_id: u16) -> bool {
    answer_id == id || answer_id == protocol::frame::UNKNOWN_REQUEST_ID
}

/// A request's name, for messages.
pub(super) fn request_name(request: &Request) -> &'static str {
    match request {
        Request::Hello { .. } => "Hello",
        Request::Configure(_) => "Configure",
        Request::Capture { .. } => "Capture",
        Request::Cancel => "Cancel",
        Request::ClearPositions => "ClearPositions",
        Request::FitSixPosition => "FitSixPosition",
        Request::GetCalibration(_) => "GetCalibration",
        Request::SetCalibration(_) => "SetCalibration",
        Request::SaveCalibration => "SaveCalibration",
        Request::EraseCalibration => "EraseCalibration",
        Request::Stream { .. } => "Stream",
        Request::TakeTemperatureBins => "TakeTemperatureBins",
        Request::FitOrtho9 => "FitOrtho9",
        Request::CaptureUntil(_) => "CaptureUntil",
        Request::Register { .. } => "Register",
        Request::StoreSelfTest(_) => "StoreSelfTest",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_request_s_own_id_or_the_unreadable_frame_id_answers_it() {
        assert!(answers(7, 7));
        assert!(answers(7, protocol::frame::UNKNOWN_REQUEST_ID));
        assert!(!answers(7, 6));
        assert!(!answers(7, 8));
    }

    /// A port whose answer arrives while the host is busy elsewhere: the first read returns only
    /// once the silence limit has passed, with the whole answer in it.
    struct ReadLate {
        answer: Vec<u8>,
    }

    impl std::io::Read for ReadLate {
        fn read(&mut self, buffer: &mut [u8]) -> std::io::Result<usize> {
            if self.answer.is_empty() {
                return Err(ErrorKind::TimedOut.into());
            }
            std::thread::sleep(SILENCE_LIMIT + READ_SLICE);
            let n = buffer.len().min(self.answer.len());
            buffer[..n].copy_from_slice(&self.answer[..n]);
            self.answer.drain(..n);
            Ok(n)
        }
    }

    impl std::io::Write for ReadLate {
        fn write(&mut self, bytes: &[u8]) -> std::io::Result<usize> {
            Ok(bytes.len())
        }

        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }

    impl Port for ReadLate {
        fn set_read_timeout(&mut self, _: Duration) -> std::io::Result<()> {
            Ok(())
        }
    }

    #[test]
    fn an_answer_read_after_the_silence_limit_is_taken_not_called_foreign_bytes() {
        let mut frame = [0u8; MAX_FRAME_LEN];
        let len = protocol::encode(1, &Response::Done, &mut frame).unwrap();
        let port = ReadLate { answer: frame[..len].to_vec() };
        let decoded = VecDeque::new();
        let mut client = Client { port, accumulator: FrameAccumulator::new(), decoded, next_id: 1, interrupt: None };
        assert!(matches!(client.call(Request::SaveCalibration), Ok(Response::Done)));
    }
}
