//! The protocol client: requests out, responses in, over any [`Port`], never waiting forever.

use std::io::ErrorKind;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use accelcal_core::link::{Call, Exchange, Step};
use shared::protocol::{DeviceInfo, Request, Response};

use super::port::Port;
use super::LinkError;

/// How long one read waits, so that silence is noticed promptly.
const READ_SLICE: Duration = Duration::from_millis(50);

/// A connection to one device: the port and the clock, driving the core's [`Exchange`].
pub struct Client<P: Port> {
    port: P,
    exchange: Exchange,
    /// The origin of the times the exchange is given.
    opened: Instant,
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
        let mut client =
            Client { port, exchange: Exchange::new(Duration::ZERO), opened: Instant::now(), interrupt: None };
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
        self.exchange.listen(self.now());
        let mut call = Call::new(id);
        loop {
            // NOTE: the device ends the cancelled operation with its final response, awaited below.
            if self.interrupted() && call.interrupt() {
                self.cancel()?;
            }
            let (answer_id, response) = self.receive().map_err(|error| call.failed(error))?;
            match call.answered(answer_id, response) {
                Step::Ignore => {}
                Step::Update(update) => {
                    if !on_update(&update) && call.decline() {
                        self.cancel()?;
                    }
                }
                Step::Done(result) => return result,
            }
        }
    }

    /// Asks the device to stop its capture or stream (the running `run` then ends).
    pub fn cancel(&mut self) -> Result<(), LinkError> {
        self.send(&Request::Cancel).map(|_| ())
    }

    fn send(&mut self, request: &Request) -> Result<u16, LinkError> {
        let (id, frame) = self.exchange.send(request)?;
        self.port.write_all(&frame).map_err(LinkError::disconnected)?;
        self.port.flush().map_err(LinkError::disconnected)?;
        Ok(id)
    }

    /// The time since the connection opened, as the exchange is given it.
    fn now(&self) -> Duration {
        self.opened.elapsed()
    }

    /// The next answer (with the id it answers), reading the port until one comes or the silence
    /// limit passes.
    fn receive(&mut self) -> Result<(u16, Response), LinkError> {
        let mut buffer = [0u8; 256];
        loop {
            if let Some(answer) = self.exchange.answer(self.now())? {
                return Ok(answer);
            }
            match self.port.read(&mut buffer) {
                Ok(0) => return Err(LinkError::Disconnected { reason: "end of stream".into() }),
                Ok(n) => self.exchange.received(&buffer[..n]),
                Err(e) if matches!(e.kind(), ErrorKind::TimedOut | ErrorKind::WouldBlock | ErrorKind::Interrupted) => {}
                Err(e) => return Err(LinkError::disconnected(e)),
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::limits::SILENCE_LIMIT;
    use shared::protocol::{self, MAX_FRAME_LEN};

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
        let mut client =
            Client { port, exchange: Exchange::new(Duration::ZERO), opened: Instant::now(), interrupt: None };
        assert!(matches!(client.call(Request::SaveCalibration), Ok(Response::Done)));
    }
}
