//! The simulated board's service loop: commands from its owner, then one step of the board's own
//! serve cycle (read, hand to the link, poll, drain responses, encode, write).
//!
//! Simulated time advances 10 ms per service loop while a capture or stream is under way, as fast as
//! the loop runs, so a 10 s capture takes a fraction of that. While idle it follows the [`Clock`]:
//! about real speed, or not at all (lockstep), which makes a run depend on its seed alone.

use std::io::ErrorKind;
use std::sync::mpsc::{Receiver, TryRecvError};
use std::time::Duration;

use embassy_futures::block_on;
use firmware::device::Device;
use firmware::server::Server;
use firmware::sim::{SimFlash, SimMpu6050, SIM_FLASH_RANGE};

use super::board::SimCommand;
use super::Port;

/// Simulated time per service loop, in microseconds.
const TICK_US: u64 = 10_000;
/// Read wait while idle: simulated time then runs at about real speed.
const IDLE_WAIT: Duration = Duration::from_millis(10);

type SimServer = Server<SimMpu6050, SimFlash>;

/// How simulated time passes while the board is idle.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Clock {
    /// At about real speed: the sensor keeps sampling between requests, as a real one does.
    RealTime,
    /// Not at all: time passes only while the board works, so the samples a run sees depend on
    /// the seed and the requests alone, never on how fast the host happens to be.
    Lockstep,
}

/// Serves `port` until told to stop or the host end goes away; returns the flash.
pub(super) fn serve<P: Port>(
    mut port: P,
    mut server: SimServer,
    inbox: Receiver<SimCommand>,
    clock: Clock,
) -> SimFlash {
    let mut buffer = [0u8; 256];
    while let Some(received) = read(&mut port, &server, &mut buffer) {
        // NOTE: commands after the read: a command sent before a request is applied before the
        // request is handled, however the two race to this thread.
        match obey(&inbox, &mut server) {
            Next::Serve => {}
            Next::Stop => break,
            Next::Restart => match restart(server) {
                Some(rebooted) => server = rebooted,
                None => return SimFlash::default(),
            },
        }
        block_on(server.receive(&buffer[..received]));
        if clock == Clock::RealTime || server.device().is_busy() {
            server.device_mut().bus_mut().advance_us(TICK_US);
        }
        server.poll();
        let mut writing = true;
        server.drain(|frame| writing = writing && port.write_all(frame).is_ok());
        let _ = port.flush();
    }
    server.into_device().into_parts().1
}

/// What the owner's commands leave to do.
enum Next {
    Serve,
    Restart,
    Stop,
}

/// Carries out the commands waiting in `inbox`, up to a restart or a stop.
fn obey(inbox: &Receiver<SimCommand>, server: &mut SimServer) -> Next {
    loop {
        match inbox.try_recv() {
            Ok(SimCommand::Stop) | Err(TryRecvError::Disconnected) => return Next::Stop,
            Ok(SimCommand::Restart) => return Next::Restart,
            Ok(command) => turn(server, command),
            Err(TryRecvError::Empty) => return Next::Serve,
        }
    }
}

/// Applies a command to the simulated sensor.
fn turn(server: &mut SimServer, command: SimCommand) {
    let device = server.device_mut();
    match command {
        SimCommand::Place(up) => device.bus_mut().place(up),
        SimCommand::Move(motion) => device.bus_mut().set_motion(motion),
        SimCommand::Connect(connected) => device.bus_mut().set_connected(connected),
        SimCommand::Restart | SimCommand::Stop => {}
    }
}

/// Reboots the board on its own sensor, flash and serial number (RAM state is lost).
fn restart(server: SimServer) -> Option<SimServer> {
    let serial = server.device().serial();
    let (sensor, flash) = server.into_device().into_parts();
    block_on(Device::boot(sensor, flash, SIM_FLASH_RANGE, serial)).ok().map(Server::new)
}

/// Reads what the host sent (waiting a little while idle); `None` when the host end is gone.
fn read<P: Port>(port: &mut P, server: &SimServer, buffer: &mut [u8]) -> Option<usize> {
    let wait = if server.device().is_busy() { Duration::ZERO } else { IDLE_WAIT };
    let _ = port.set_read_timeout(wait);
    match port.read(buffer) {
        Ok(n) => Some(n),
        Err(e) if matches!(e.kind(), ErrorKind::TimedOut | ErrorKind::WouldBlock | ErrorKind::Interrupted) => Some(0),
        Err(e) if e.kind() == ErrorKind::BrokenPipe => None, // the in-process host is gone
        Err(_) => {
            std::thread::sleep(IDLE_WAIT); // a pty with no one on the other side yet
            Some(0)
        }
    }
}
