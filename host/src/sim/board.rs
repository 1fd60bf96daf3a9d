//! A running simulated board and the commands that turn it.

use std::sync::mpsc::{channel, Sender};
use std::thread::JoinHandle;

use embassy_futures::block_on;
use firmware::device::Device;
use firmware::server::Server;
use firmware::sim::physics::{Motion, TrueErrors};
use firmware::sim::{sim_serial_number, SimFlash, SimMpu6050, SIM_FLASH_RANGE};

use super::serve::{serve, Clock};
use super::Port;
use crate::link::{pipe, Connection, LinkError};

/// What the owner of a simulated board can do to it.
#[derive(Debug, Clone, PartialEq)]
pub enum SimCommand {
    /// Rest the board with this body-frame direction pointing up.
    Place([f32; 3]),
    /// Start moving.
    Move(Motion),
    /// Disconnect or reconnect the sensor.
    Connect(bool),
    /// Reboot the board (a reset or brown-out): RAM state is lost, the flash and the port stay.
    Restart,
    /// Stop serving and hand the flash back.
    Stop,
}

/// A running simulated board.
pub struct SimBoard {
    commands: Sender<SimCommand>,
    thread: Option<JoinHandle<SimFlash>>,
    truth: TrueErrors,
}

impl SimBoard {
    /// Boots a board on `flash` (keep it across `stop` and `spawn` to simulate a restart), with the
    /// published error model and noise seeded by `seed`, and serves `port` until stopped.
    pub fn spawn<P: Port + 'static>(port: P, flash: SimFlash, seed: u64) -> Self {
        Self::spawn_with_clock(port, flash, seed, Clock::RealTime)
    }

    /// [`SimBoard::spawn`], with simulated time passing while idle as `clock` says.
    fn spawn_with_clock<P: Port + 'static>(port: P, flash: SimFlash, seed: u64, clock: Clock) -> Self {
        let sensor = SimMpu6050::new(seed);
        let truth = sensor.physics.truth;
        let (commands, inbox) = channel();
        let thread = std::thread::spawn(move || {
            // NOTE: boot fails only for a flash range that does not fit the flash, and
            // SIM_FLASH_RANGE is the whole of SimFlash; the board then simply never answers.
            match block_on(Device::boot(sensor, flash, SIM_FLASH_RANGE, sim_serial_number(seed))) {
                Ok(device) => serve(port, Server::new(device), inbox, clock),
                Err(_) => SimFlash::default(),
            }
        });
        SimBoard { commands, thread: Some(thread), truth }
    }

    /// A fresh simulated board in this process, behind an in-memory pipe, and a session with it; its
    /// clock runs in lockstep with the requests, so a run is repeatable by its seed.
    pub fn in_process(seed: u64) -> Result<(Connection, SimBoard), LinkError> {
        let (host_end, device_end) = pipe();
        let board = SimBoard::spawn_with_clock(device_end, SimFlash::new(), seed, Clock::Lockstep);
        Ok((Connection::over(Box::new(host_end))?, board))
    }

    /// A handle that turns the board: for the procedure's simulated hand, and for tests.
    pub fn controls(&self) -> Sender<SimCommand> {
        self.commands.clone()
    }

    /// The simulated sensor's true errors (its true calibration).
    pub fn truth(&self) -> TrueErrors {
        self.truth
    }

    /// Stops the board and returns its flash.
    pub fn stop(mut self) -> SimFlash {
        let _ = self.commands.send(SimCommand::Stop);
        self.thread.take().and_then(|t| t.join().ok()).unwrap_or_default()
    }
}

impl Drop for SimBoard {
    fn drop(&mut self) {
        let _ = self.commands.send(SimCommand::Stop);
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}
