//! The protocol client: the core's [`Link`] over a [`Port`] and this process's clock, never waiting
//! forever; its requests blocking, one method each.

use std::io::ErrorKind;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use accelcal_core::link::{ChipOrtho9, Link, StreamRequest, Tally, Transport};
use embassy_futures::block_on;
use shared::protocol::{CalibrationSlot, CaptureGoal, CaptureProgress, CaptureStats, DeviceInfo, Request, Response};
use shared::protocol::{Sample, SensorConfig, TempBin};
use shared::selftest::StoredSelfTest;
use shared::{Calibration, Position};

use super::port::Port;
use super::LinkError;

/// How long one read waits, so that silence is noticed promptly.
const READ_SLICE: Duration = Duration::from_millis(50);

/// A port as the core's link moves bytes over it: reads that wait [`READ_SLICE`] at most, the time
/// since it was opened, and the Ctrl-C flag.
pub struct PortTransport<P: Port> {
    port: P,
    opened: Instant,
    interrupt: Option<Arc<AtomicBool>>,
}

// NOTE: every future here is ready when first polled: the port blocks, as the command line wants.
impl<P: Port> Transport for PortTransport<P> {
    async fn write(&mut self, bytes: &[u8]) -> Result<(), LinkError> {
        self.port.write_all(bytes).map_err(LinkError::disconnected)?;
        self.port.flush().map_err(LinkError::disconnected)
    }

    async fn read(&mut self, buffer: &mut [u8]) -> Result<usize, LinkError> {
        match self.port.read(buffer) {
            Ok(0) => Err(LinkError::Disconnected { reason: "end of stream".into() }),
            Ok(n) => Ok(n),
            Err(e) if matches!(e.kind(), ErrorKind::TimedOut | ErrorKind::WouldBlock | ErrorKind::Interrupted) => Ok(0),
            Err(e) => Err(LinkError::disconnected(e)),
        }
    }

    fn now(&self) -> Duration {
        self.opened.elapsed()
    }

    fn unix_time_s(&self) -> f64 {
        crate::session::unix_time_s()
    }

    fn interrupted(&self) -> bool {
        self.interrupt.as_ref().is_some_and(|flag| flag.load(Ordering::SeqCst))
    }
}

/// A connection to one device: the core's link over a port, each request blocking until answered.
pub struct Client<P: Port> {
    link: Link<PortTransport<P>>,
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
        let mut client = Client::over(port);
        let said = block_on(client.link.delimit());
        match said.and_then(|()| client.hello()) {
            Ok(info) => Ok((client, info)),
            Err(error) => Err((error, client.link.into_transport().port)),
        }
    }

    fn over(port: P) -> Self {
        Client { link: Link::new(PortTransport { port, opened: Instant::now(), interrupt: None }) }
    }

    /// The core's link under this client, for the core's run to drive.
    pub fn link(&mut self) -> &mut Link<PortTransport<P>> {
        &mut self.link
    }

    /// Once `flag` is set (by Ctrl-C), the running capture or stream is cancelled on the device and
    /// every request ends with [`LinkError::Interrupted`].
    pub fn interrupt_on(&mut self, flag: Arc<AtomicBool>) {
        self.link.transport_mut().interrupt = Some(flag);
    }

    /// Takes the Ctrl-C flag away (until given again), for what must still be said to the device
    /// after an interruption (writing its configuration back).
    pub fn take_interrupt(&mut self) -> Option<Arc<AtomicBool>> {
        self.link.transport_mut().interrupt.take()
    }

    /// A request that completes at once: its final response; a device error becomes `Err`.
    pub fn call(&mut self, request: Request) -> Result<Response, LinkError> {
        block_on(self.link.call(request))
    }

    /// A request with progress (capture) or samples (stream): each goes to `on_update`; returns the
    /// final response.
    pub fn run(&mut self, request: Request, on_update: impl FnMut(&Response)) -> Result<Response, LinkError> {
        block_on(self.link.run(request, on_update))
    }

    /// As [`Client::run`]; once `on_update` returns `false` the device is asked to stop.
    pub fn run_while(
        &mut self,
        request: Request,
        on_update: impl FnMut(&Response) -> bool,
    ) -> Result<Response, LinkError> {
        block_on(self.link.run_while(request, on_update))
    }

    /// Asks the device to stop its capture or stream.
    pub fn cancel(&mut self) -> Result<(), LinkError> {
        block_on(self.link.cancel())
    }

    /// Says hello (again: the device's state now); refuses a device of another protocol version.
    pub fn hello(&mut self) -> Result<DeviceInfo, LinkError> {
        block_on(self.link.hello())
    }

    /// Averages the still sensor for `seconds`, reporting progress.
    pub fn capture(
        &mut self,
        seconds: u8,
        on_progress: impl FnMut(&CaptureProgress),
    ) -> Result<(CaptureStats, Option<Position>), LinkError> {
        block_on(self.link.capture(seconds, on_progress))
    }

    /// Averages the still sensor until `goal` stops it, reporting progress.
    pub fn capture_until(
        &mut self,
        goal: CaptureGoal,
        on_progress: impl FnMut(&CaptureProgress),
    ) -> Result<(CaptureStats, Option<Position>), LinkError> {
        block_on(self.link.capture_until(goal, on_progress))
    }

    /// Sets range, sample rate and filter; the configuration the device achieved.
    pub fn configure(&mut self, config: SensorConfig) -> Result<SensorConfig, LinkError> {
        block_on(self.link.configure(config))
    }

    /// Streams samples, each to `on_sample`; what arrived and what was lost.
    pub fn stream(&mut self, wanted: StreamRequest, on_sample: impl FnMut(&Sample)) -> Result<Tally, LinkError> {
        block_on(self.link.stream(wanted, on_sample))
    }

    /// As [`Client::stream`]; once `on_sample` returns `false` the stream is cancelled on the board.
    pub fn stream_while(
        &mut self,
        wanted: StreamRequest,
        on_sample: impl FnMut(&Sample) -> bool,
    ) -> Result<Tally, LinkError> {
        block_on(self.link.stream_while(wanted, on_sample))
    }

    /// The active or the stored calibration; `None` when the slot is empty.
    pub fn calibration(&mut self, slot: CalibrationSlot) -> Result<Option<Calibration>, LinkError> {
        block_on(self.link.calibration(slot))
    }

    /// Makes a calibration active (until reset, or until saved).
    pub fn set_calibration(&mut self, calibration: Calibration) -> Result<(), LinkError> {
        block_on(self.link.set_calibration(calibration))
    }

    /// Stores the active calibration in flash.
    pub fn save_calibration(&mut self) -> Result<(), LinkError> {
        block_on(self.link.save_calibration())
    }

    /// Erases the stored calibration.
    pub fn erase_calibration(&mut self) -> Result<(), LinkError> {
        block_on(self.link.erase_calibration())
    }

    /// Forgets the captures kept for the chip's fits.
    pub fn clear_positions(&mut self) -> Result<(), LinkError> {
        block_on(self.link.clear_positions())
    }

    /// Every temperature bin the chip holds, coolest first; the chip's bins are then empty.
    pub fn take_temperature_bins(&mut self) -> Result<Vec<TempBin>, LinkError> {
        block_on(self.link.take_temperature_bins())
    }

    /// The on-chip six-position fit of the captures the device kept.
    pub fn fit_six_position(&mut self) -> Result<Calibration, LinkError> {
        block_on(self.link.fit_six_position())
    }

    /// The chip's 9-parameter (`ortho9`) fit of the captures it kept since they were last cleared.
    pub fn fit_ortho9(&mut self) -> Result<ChipOrtho9, LinkError> {
        block_on(self.link.fit_ortho9())
    }

    /// Writes `write` to a sensor register when given, then reads it: the value it holds.
    pub fn register(&mut self, register: u8, write: Option<u8>) -> Result<u8, LinkError> {
        block_on(self.link.register(register, write))
    }

    /// `count` consecutive sensor registers from `first`, one request each.
    pub fn read_registers(&mut self, first: u8, count: u8) -> Result<Vec<u8>, LinkError> {
        block_on(self.link.read_registers(first, count))
    }

    /// Writes one sensor register; the value it holds afterwards.
    pub fn write_register(&mut self, register: u8, value: u8) -> Result<u8, LinkError> {
        block_on(self.link.write_register(register, value))
    }

    /// Keeps a self-test in the board's flash in place of the one before (every hello carries it).
    pub fn store_self_test(&mut self, self_test: &StoredSelfTest) -> Result<(), LinkError> {
        block_on(self.link.store_self_test(self_test))
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
        let mut client = Client::over(port);
        assert!(matches!(client.call(Request::SaveCalibration), Ok(Response::Done)));
    }
}
