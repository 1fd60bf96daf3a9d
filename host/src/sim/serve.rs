//! The simulated board's service loop: commands from its owner, then one step of the board's own
//! serve cycle (read, hand to the link, poll, drain responses, encode, write).
//!
//! Simulated time advances 10 ms per service loop: at the pace of real time while idle, as fast as
//! the loop runs while a capture or stream is under way, so a 10 s capture takes a fraction of that.

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

/// Serves `port` until told to stop or the host end goes away; returns the flash.
pub(super) fn serve<P: Port>(mut port: P, mut server: SimServer, inbox: Receiver<SimCommand>) -> SimFlash {
    'serving: loop {
        // NOTE: every waiting command is applied before the port is read, so a command sent before
        // a request is in force when the device answers a request sent after it.
        loop {
            match inbox.try_recv() {
                Ok(SimCommand::Stop) | Err(TryRecvError::Disconnected) => break 'serving,
                Ok(SimCommand::Restart) => match restart(server) {
                    Some(rebooted) => server = rebooted,
                    None => return SimFlash::default(),
                },
                Ok(command) => turn(&mut server, command),
                Err(TryRecvError::Empty) => break,
            }
        }
        if !step(&mut port, &mut server) {
            break;
        }
    }
    server.into_device().into_parts().1
}

/// Applies a command to the simulated sensor.
fn turn(server: &mut SimServer, command: SimCommand) {
    let device = server.device_mut();
    match command {
        SimCommand::Place(up) => device.bus_mut().place(up),
        SimCommand::Move(motion) => device.bus_mut().set_motion(motion),
        SimCommand::Connect(connected) => device.bus_mut().set_connected(connected),
        SimCommand::Ambient { target_c, c_per_s } => device.bus_mut().physics.environment.ramp_to(target_c, c_per_s),
        SimCommand::Elapse(seconds) => soak(device.bus_mut(), seconds),
        SimCommand::Restart | SimCommand::Stop => {}
    }
}

/// Lets `seconds` pass in steps short enough for a ramp of the surroundings to stay smooth.
fn soak(sensor: &mut SimMpu6050, seconds: f32) {
    const STEP_S: f32 = 5.0;
    let mut left = seconds;
    while left > 0.0 {
        sensor.elapse_seconds(left.min(STEP_S));
        left -= STEP_S;
    }
}

/// Reboots the board on its own sensor, flash and serial number (RAM state is lost).
fn restart(server: SimServer) -> Option<SimServer> {
    let serial = server.device().serial();
    let (sensor, flash) = server.into_device().into_parts();
    block_on(Device::boot(sensor, flash, SIM_FLASH_RANGE, serial)).ok().map(Server::new)
}

/// One service cycle; `false` when the host end is gone.
fn step<P: Port>(port: &mut P, server: &mut SimServer) -> bool {
    let mut buffer = [0u8; 256];
    let wait = if server.device().is_busy() { Duration::ZERO } else { IDLE_WAIT };
    let _ = port.set_read_timeout(wait);
    match port.read(&mut buffer) {
        Ok(n) => block_on(server.receive(&buffer[..n])),
        Err(e) if matches!(e.kind(), ErrorKind::TimedOut | ErrorKind::WouldBlock | ErrorKind::Interrupted) => {}
        Err(e) if e.kind() == ErrorKind::BrokenPipe => return false, // the in-process host is gone
        Err(_) => std::thread::sleep(IDLE_WAIT),                     // a pty with no one on the other side yet
    }
    server.device_mut().bus_mut().advance_us(TICK_US);
    server.poll();
    let mut writing = true;
    server.drain(|frame| writing = writing && port.write_all(frame).is_ok());
    let _ = port.flush();
    true
}
