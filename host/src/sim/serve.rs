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
use firmware::link::Link;
use firmware::sim::{SimFlash, SimMpu6050, SIM_FLASH_RANGE};
use shared::protocol::MAX_FRAME_LEN;

use super::board::SimCommand;
use super::Port;

/// Simulated time per service loop, in microseconds.
const TICK_US: u64 = 10_000;
/// Read wait while idle: simulated time then runs at about real speed.
const IDLE_WAIT: Duration = Duration::from_millis(10);

type SimDevice = Device<SimMpu6050, SimFlash>;

/// Serves `port` until told to stop or the host end goes away; returns the flash.
pub(super) fn serve<P: Port>(mut port: P, mut device: SimDevice, inbox: Receiver<SimCommand>) -> SimFlash {
    let mut link = Link::new();
    loop {
        match inbox.try_recv() {
            Ok(SimCommand::Stop) | Err(TryRecvError::Disconnected) => break,
            Ok(SimCommand::Restart) => match restart(device) {
                Some(rebooted) => (device, link) = (rebooted, Link::new()),
                None => return SimFlash::default(),
            },
            Ok(command) => turn(&mut device, command),
            Err(TryRecvError::Empty) => {}
        }
        if !step(&mut port, &mut device, &mut link) {
            break;
        }
    }
    device.into_parts().1
}

/// Applies a command to the simulated sensor.
fn turn(device: &mut SimDevice, command: SimCommand) {
    match command {
        SimCommand::Place(up) => device.bus_mut().place(up),
        SimCommand::Move(motion) => device.bus_mut().set_motion(motion),
        SimCommand::Connect(connected) => device.bus_mut().set_connected(connected),
        SimCommand::Restart | SimCommand::Stop => {}
    }
}

/// Reboots the board on its own sensor and flash (RAM state is lost).
fn restart(device: SimDevice) -> Option<SimDevice> {
    let (sensor, flash) = device.into_parts();
    block_on(Device::boot(sensor, flash, SIM_FLASH_RANGE)).ok()
}

/// One service cycle; `false` when the host end is gone.
fn step<P: Port>(port: &mut P, device: &mut SimDevice, link: &mut Link) -> bool {
    let mut buffer = [0u8; 256];
    let wait = if device.is_busy() { Duration::ZERO } else { IDLE_WAIT };
    let _ = port.set_read_timeout(wait);
    match port.read(&mut buffer) {
        Ok(n) => block_on(link.receive(&buffer[..n], device)),
        Err(e) if matches!(e.kind(), ErrorKind::TimedOut | ErrorKind::WouldBlock | ErrorKind::Interrupted) => {}
        Err(e) if e.kind() == ErrorKind::BrokenPipe => return false, // the in-process host is gone
        Err(_) => std::thread::sleep(IDLE_WAIT),                     // a pty with no one on the other side yet
    }
    device.bus_mut().advance_us(TICK_US);
    device.poll();
    write_responses(port, device);
    true
}

/// Encodes and writes every response the device has ready.
fn write_responses<P: Port>(port: &mut P, device: &mut SimDevice) {
    while let Some((id, response)) = device.next_response() {
        let mut frame = [0u8; MAX_FRAME_LEN];
        if port.write_all(Link::encode(id, &response, &mut frame)).is_err() {
            break;
        }
    }
    let _ = port.flush();
}
