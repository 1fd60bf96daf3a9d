//! The simulated board: the firmware library's own `Device` on the simulated MPU-6050 and a RAM flash,
//! served over any [`Port`] from a thread, exactly as the real board serves its USB port.
//!
//! Simulated time advances 10 ms per service loop: at the pace of real time while idle, as fast as
//! the loop runs while a capture or stream is under way, so a 10 s capture takes a fraction of that.

use std::io::ErrorKind;
use std::sync::mpsc::{channel, Sender, TryRecvError};
use std::thread::JoinHandle;
use std::time::Duration;

use embassy_futures::block_on;
use firmware::device::Device;
use firmware::server::Server;
use firmware::sim::physics::{Motion, TrueErrors};
use firmware::sim::{sim_serial_number, SimFlash, SimMpu6050, SIM_FLASH_RANGE};

use crate::port::Port;

/// Simulated time per service loop, in microseconds.
const TICK_US: u64 = 10_000;
/// Read wait while idle: simulated time then runs at about real speed.
const IDLE_WAIT: Duration = Duration::from_millis(10);

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
        let sensor = SimMpu6050::new(seed);
        let truth = sensor.physics.truth;
        let (commands, inbox) = channel();
        let thread = std::thread::spawn(move || {
            // NOTE: boot fails only for a flash range that does not fit the flash, and
            // SIM_FLASH_RANGE is the whole of SimFlash; the board then simply never answers.
            match block_on(Device::boot(sensor, flash, SIM_FLASH_RANGE, sim_serial_number(seed))) {
                Ok(device) => serve(port, Server::new(device), inbox),
                Err(_) => SimFlash::default(),
            }
        });
        SimBoard { commands, thread: Some(thread), truth }
    }

    /// A handle that turns the board, for the guided procedure.
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

fn serve<P: Port>(
    mut port: P,
    mut server: Server<SimMpu6050, SimFlash>,
    inbox: std::sync::mpsc::Receiver<SimCommand>,
) -> SimFlash {
    let mut buffer = [0u8; 256];
    loop {
        let device = server.device_mut();
        match inbox.try_recv() {
            Ok(SimCommand::Place(up)) => device.bus_mut().place(up),
            Ok(SimCommand::Move(motion)) => device.bus_mut().set_motion(motion),
            Ok(SimCommand::Connect(connected)) => device.bus_mut().set_connected(connected),
            Ok(SimCommand::Restart) => {
                let serial = server.device().serial();
                let (sensor, flash) = server.into_device().into_parts();
                match block_on(Device::boot(sensor, flash, SIM_FLASH_RANGE, serial)) {
                    Ok(rebooted) => server = Server::new(rebooted),
                    Err(_) => return SimFlash::default(),
                }
            }
            Ok(SimCommand::Stop) | Err(TryRecvError::Disconnected) => break,
            Err(TryRecvError::Empty) => {}
        }
        let wait = if server.device().is_busy() { Duration::ZERO } else { IDLE_WAIT };
        let _ = port.set_read_timeout(wait);
        match port.read(&mut buffer) {
            Ok(n) => block_on(server.receive(&buffer[..n])),
            Err(e) if matches!(e.kind(), ErrorKind::TimedOut | ErrorKind::WouldBlock | ErrorKind::Interrupted) => {}
            Err(e) if e.kind() == ErrorKind::BrokenPipe => break, // the in-process host is gone
            Err(_) => std::thread::sleep(IDLE_WAIT),              // a pty with no one on the other side yet
        }
        server.device_mut().bus_mut().advance_us(TICK_US);
        server.poll();
        // NOTE: after a failed write the rest of the frames are dropped: the host is gone.
        let mut writing = true;
        server.drain(|frame| writing = writing && port.write_all(frame).is_ok());
        let _ = port.flush();
    }
    server.into_device().into_parts().1
}

/// The tool's own hand on the simulated board: it turns the board to each target, a few degrees off
/// at random as a person's hand would, and to random orientations for verification.
pub struct SimHand {
    controls: Sender<SimCommand>,
    rng: rand_xoshiro::Xoshiro256PlusPlus,
    placement_deg: f64,
    verified: Vec<[f64; 3]>,
}

impl SimHand {
    /// A hand on the board behind `controls`, off by about `placement_deg` (random axis, normal
    /// angle), repeatable by `seed`.
    pub fn new(controls: Sender<SimCommand>, placement_deg: f64, seed: u64) -> Self {
        use rand_xoshiro::rand_core::SeedableRng;
        SimHand {
            controls,
            rng: rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(seed),
            placement_deg,
            verified: Vec::new(),
        }
    }

    fn place(&mut self, up: [f64; 3]) -> Result<(), crate::error::Error> {
        self.controls
            .send(SimCommand::Place(up.map(|v| v as f32)))
            .map_err(|_| crate::error::Error::Disconnected { reason: "the simulated board stopped".into() })
    }
}

impl crate::calibrate::Hand for SimHand {
    fn present(
        &mut self,
        target: &crate::calibrate::Target,
        _: &mut dyn crate::calibrate::Feedback,
    ) -> Result<(), crate::error::Error> {
        use shared::linalg::{add, cross, norm, scale};
        // Tilt `up` by a normally distributed angle about a random axis perpendicular to it.
        let axis = cross(target.up, crate::synthetic::random_unit(&mut self.rng));
        let axis = scale(axis, 1.0 / norm(axis));
        let angle = (self.placement_deg * crate::synthetic::gaussian(&mut self.rng)).to_radians();
        let tilted = add(scale(target.up, angle.cos()), scale(cross(axis, target.up), angle.sin()));
        self.place(tilted)
    }

    fn fresh(&mut self, _: usize, _: &mut dyn crate::calibrate::Feedback) -> Result<(), crate::error::Error> {
        // A new random orientation, well clear of those verified before (a person turns the board
        // somewhere new; the procedure insists on it).
        let clear = crate::calibrate::FRESH_DEG + 10.0;
        let mut up = crate::synthetic::random_unit(&mut self.rng);
        for _ in 0..1000 {
            if self.verified.iter().all(|v| shared::orientation::angle_between_deg(up, *v) >= clear) {
                break;
            }
            up = crate::synthetic::random_unit(&mut self.rng);
        }
        self.verified.push(up);
        self.place(up)
    }
}
