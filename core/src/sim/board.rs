//! A simulated board in this process with no thread and no port: the firmware's own serve step on
//! the simulated MPU-6050, run by the host's reads. Its time runs in lockstep with the requests, as
//! the host's threaded board in lockstep does: it moves 10 ms at a step only while the board works and
//! only once the host has read all it was sent, so a run depends on its seed and its requests alone.
//! It builds for the browser, where it is the page's board without hardware.

use std::cell::RefCell;
use std::rc::Rc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::Duration;

use embassy_futures::block_on;
use firmware::device::Device;
use firmware::server::Server;
use firmware::sim::{sim_serial_number, SimFlash, SimMpu6050, SIM_FLASH_RANGE};

use super::command::SimCommand;
use super::owner_hand::OwnerHand;
use super::simulated_hand::{Controls, Stopped};
use crate::link::{LinkError, Transport};
use crate::run::BoardClock;

/// Simulated time per step while the board works, in microseconds (the threaded board's tick).
const TICK_US: u64 = 10_000;
/// Host time that passes on a read that found nothing while the board is idle, in microseconds:
/// simulated time stands still then, and a board that never answers must still meet the silence limit.
const IDLE_READ_US: u64 = 1_000;
/// The date the in-process board's run begins at (2026-01-01), in seconds since the Unix epoch: a
/// date of its own, so that the records a run keeps depend on its seed alone.
const EPOCH_S: f64 = 1_767_225_600.0;

type SimServer = Server<SimMpu6050, SimFlash>;

/// The board and what it has written that the host has not read.
struct Served {
    server: SimServer,
    hand: OwnerHand,
    /// Bytes the host wrote, not yet handed to the board.
    inbox: Vec<u8>,
    /// Frames the board wrote, not yet read by the host.
    outgoing: Vec<u8>,
    /// Host time spent on reads that found nothing while the board was idle, in microseconds.
    idle_us: u64,
    /// The board's own time, in microseconds, for the run's board clock.
    board_us: Arc<AtomicU64>,
}

/// The transport to a simulated board in this process.
pub struct InProcess {
    served: Rc<RefCell<Served>>,
}

/// The hand's way to the board of an [`InProcess`] transport.
pub struct BoardControls {
    served: Rc<RefCell<Served>>,
}

impl InProcess {
    /// A board booted on `sensor` with an empty flash and the serial number of `seed`.
    pub fn boot(sensor: SimMpu6050, seed: u64) -> Self {
        // NOTE: boot fails only for a flash range larger than the flash; SIM_FLASH_RANGE is all of it.
        let device = block_on(Device::boot(sensor, SimFlash::new(), SIM_FLASH_RANGE, sim_serial_number(seed)))
            .unwrap_or_else(|_| unreachable!("SIM_FLASH_RANGE fits SimFlash"));
        let served = Served {
            server: Server::new(device),
            hand: OwnerHand::default(),
            inbox: Vec::new(),
            outgoing: Vec::new(),
            idle_us: 0,
            board_us: Arc::new(AtomicU64::new(0)),
        };
        InProcess { served: Rc::new(RefCell::new(served)) }
    }

    /// The simulated MPU-6050 as the threaded board's realistic sensor is: just powered on in a
    /// 20 degC room, its noise seeded by `seed`.
    pub fn realistic(seed: u64) -> Self {
        let mut sensor = SimMpu6050::new(seed).with_part(firmware::sim::part::SimPart::mpu6050());
        sensor.physics.power_on(0, 0.0);
        Self::boot(sensor, seed)
    }

    /// A handle the simulated hand turns the board with.
    pub fn controls(&self) -> BoardControls {
        BoardControls { served: self.served.clone() }
    }

    /// A reader of the board's own time since power-on, in seconds.
    pub fn clock(&self) -> BoardClock {
        let board_us = self.served.borrow().board_us.clone();
        Arc::new(move || board_us.load(Ordering::Relaxed) as f64 * 1e-6)
    }
}

impl Served {
    /// One step of the serve loop, taken when the host waits with nothing left to read: what the
    /// host wrote goes to the board, time passes while it works, and what it answers is queued.
    fn step(&mut self) {
        let bytes = std::mem::take(&mut self.inbox);
        block_on(self.server.receive(&bytes));
        let busy = self.server.device().is_busy();
        let step_us = if busy { TICK_US } else { 0 };
        self.hand.advance(self.server.device_mut().bus_mut(), step_us);
        let now_us = self.server.device_mut().bus_mut().now_us();
        self.board_us.store(now_us, Ordering::Relaxed);
        block_on(self.server.poll());
        let outgoing = &mut self.outgoing;
        self.server.drain(|frame| outgoing.extend_from_slice(frame));
        if !busy && self.outgoing.is_empty() {
            self.idle_us += IDLE_READ_US;
        }
    }

    fn now(&mut self) -> Duration {
        Duration::from_micros(self.server.device_mut().bus_mut().now_us() + self.idle_us)
    }
}

impl Transport for InProcess {
    async fn write(&mut self, bytes: &[u8]) -> Result<(), LinkError> {
        self.served.borrow_mut().inbox.extend_from_slice(bytes);
        Ok(())
    }

    async fn read(&mut self, buffer: &mut [u8]) -> Result<usize, LinkError> {
        let mut served = self.served.borrow_mut();
        if served.outgoing.is_empty() {
            served.step();
        }
        let n = buffer.len().min(served.outgoing.len());
        buffer[..n].copy_from_slice(&served.outgoing[..n]);
        served.outgoing.drain(..n);
        Ok(n)
    }

    fn now(&self) -> Duration {
        self.served.borrow_mut().now()
    }

    fn unix_time_s(&self) -> f64 {
        EPOCH_S + self.now().as_secs_f64()
    }
}

impl Controls for BoardControls {
    fn send(&mut self, command: SimCommand) -> Result<(), Stopped> {
        let mut served = self.served.borrow_mut();
        let served = &mut *served;
        match served.hand.obey(served.server.device_mut().bus_mut(), command) {
            true => Ok(()),
            // NOTE: the link's faults, restarts and stops are the threaded board's (host `sim`).
            false => Err(Stopped),
        }
    }
}
