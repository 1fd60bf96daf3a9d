//! The simulated board's service loop: commands from its owner, then one step of the board's own
//! serve cycle (read, hand to the link, poll, drain responses, encode, write).
//!
//! Simulated time runs at the [`Pace`] the board was spawned with. It stands still while written
//! frames wait for the host to read them: the board is held up, as USB holds up the real one, and
//! never drops a frame because the host is slow.

use std::io::ErrorKind;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{Receiver, TryRecvError};
use std::sync::Arc;

use embassy_futures::block_on;
use firmware::device::Device;
use firmware::server::Server;
use firmware::sim::{SimFlash, SimMpu6050, SIM_FLASH_RANGE};

use super::clock::{Clock, Pace};
use super::outgoing::Outgoing;
use super::Port;
use accelcal_core::sim::OwnerHand;
use accelcal_core::sim::SimCommand;

type SimServer = Server<SimMpu6050, SimFlash>;

/// How long a read waits while the board in lockstep waits for the host to catch up.
const HOST_CATCH_UP: std::time::Duration = std::time::Duration::from_micros(100);
/// How long to wait before reading a pseudo-terminal again that has no one on the other side yet.
const PTY_RETRY: std::time::Duration = std::time::Duration::from_millis(10);

/// The serve loop's own state beside the board: time, unwritten frames, a motion's end.
struct Service {
    clock: Clock,
    outgoing: Outgoing,
    /// The owner's hand on the sensor.
    hand: OwnerHand,
    /// The simulated time now, in microseconds, for the board's owner.
    now_us: Arc<AtomicU64>,
}

/// Serves `port` until told to stop or the host end goes away; returns the flash.
pub(super) fn serve<P: Port>(
    mut port: P,
    mut server: SimServer,
    inbox: Receiver<SimCommand>,
    pace: Pace,
    now_us: Arc<AtomicU64>,
) -> SimFlash {
    let (clock, outgoing) = (Clock::new(pace), Outgoing::default());
    let mut service = Service { clock, outgoing, hand: OwnerHand::default(), now_us };
    let mut buffer = [0u8; 256];
    'serving: while let Some(received) = service.read(&mut port, &server, &mut buffer) {
        // NOTE: the owner's commands are applied after the read and before the bytes are handled, so
        // a command sent before a request is in force when that request is answered, however the two
        // race to this thread.
        loop {
            match inbox.try_recv() {
                Ok(SimCommand::Stop) | Err(TryRecvError::Disconnected) => break 'serving,
                Ok(SimCommand::Restart) => match restart(server) {
                    Some(rebooted) => server = rebooted,
                    None => return SimFlash::default(),
                },
                Ok(command) => service.obey(&mut server, command),
                Err(TryRecvError::Empty) => break,
            }
        }
        block_on(server.receive(&buffer[..received]));
        if !service.step(&mut port, &mut server) {
            break;
        }
    }
    server.into_device().into_parts().1
}

/// Reboots the board on its own sensor, flash and serial number (RAM state is lost).
fn restart(server: SimServer) -> Option<SimServer> {
    let serial = server.device().serial();
    let (sensor, flash) = server.into_device().into_parts();
    block_on(Device::boot(sensor, flash, SIM_FLASH_RANGE, serial)).ok().map(Server::new)
}

impl Service {
    /// Applies a command to the simulated sensor or link.
    fn obey(&mut self, server: &mut SimServer, command: SimCommand) {
        if let SimCommand::LoseSamples(count) = command {
            self.outgoing.lose_samples(count);
        } else {
            self.hand.obey(server.device_mut().bus_mut(), command);
        }
    }

    /// Reads what the host sent (waiting a little unless the board works); `None` when the host
    /// end is gone.
    fn read<P: Port>(&self, port: &mut P, server: &SimServer, buffer: &mut [u8]) -> Option<usize> {
        let working = server.device().is_busy() && self.outgoing.is_empty();
        let wait = match self.waits_for_host(port, server) {
            true => HOST_CATCH_UP,
            false => self.clock.read_wait(working),
        };
        let _ = port.set_read_timeout(wait);
        match port.read(buffer) {
            Ok(n) => Some(n),
            Err(e) if matches!(e.kind(), ErrorKind::TimedOut | ErrorKind::WouldBlock | ErrorKind::Interrupted) => {
                Some(0)
            }
            Err(e) if e.kind() == ErrorKind::BrokenPipe => None, // the in-process host is gone
            Err(_) => {
                std::thread::sleep(PTY_RETRY); // a pty with no one on the other side yet
                Some(0)
            }
        }
    }

    /// The rest of one service cycle after the read: write, let time pass, poll, drain; `false`
    /// when the host end is gone.
    fn step<P: Port>(&mut self, port: &mut P, server: &mut SimServer) -> bool {
        if !self.outgoing.write(port) {
            return false;
        }
        if !self.outgoing.is_empty() {
            // NOTE: back-pressure: the board waits for the host to take what it wrote.
            self.clock.hold();
            return true;
        }
        if self.waits_for_host(port, server) {
            return true;
        }
        self.let_time_pass(server);
        block_on(server.poll());
        server.drain(|frame| self.outgoing.queue(frame));
        self.outgoing.write(port)
    }

    /// Whether the board, in lockstep and working, must let the host act on all it was sent (a
    /// cancel, say) before time moves on: so that how far a stream runs past the sample the host
    /// stopped at depends on the requests alone, never on how fast the host happens to be.
    fn waits_for_host<P: Port>(&self, port: &P, server: &SimServer) -> bool {
        self.clock.in_lockstep() && server.device().is_busy() && !port.peer_settled()
    }

    /// Advances the sensor's time (the hand ends a timed motion when it is due).
    fn let_time_pass(&mut self, server: &mut SimServer) {
        let step_us = self.clock.step_us(server.device().is_busy());
        let sensor = server.device_mut().bus_mut();
        self.hand.advance(sensor, step_us);
        self.now_us.store(sensor.now_us(), Ordering::Relaxed);
    }
}
