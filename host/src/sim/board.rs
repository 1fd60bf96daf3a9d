//! A running simulated board and the commands that turn it.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{channel, Sender};
use std::sync::Arc;
use std::thread::JoinHandle;

use embassy_futures::block_on;
use firmware::device::Device;
use firmware::server::Server;
use firmware::sim::part::SimPart;
use firmware::sim::physics::{Physics, TrueErrors};
use firmware::sim::thermal::{ThermalDrift, TRUTH_REF_TEMP_C};
use firmware::sim::{sim_serial_number, SimFlash, SimMpu6050, SIM_FLASH_RANGE};
use shared::Calibration;

use super::clock::Pace;
use super::serve::serve;
use super::Port;
use crate::link::{pipe, Connection, LinkError};
use crate::report::TruthJson;
use crate::session::Session;
use accelcal_core::run::ProcedureError;
use accelcal_core::sim::SimCommand;
use accelcal_core::sim::{SimulatedBoard, SimulatedSession};

/// Orientations [`SimBoard::true_error_mg`] averages over.
pub const TRUE_ERROR_ORIENTATIONS: usize = 200;

/// Which simulated MPU-6050 a board carries.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum SimSensor {
    /// Just powered on in a 20 degC room: it warms, drifts with temperature, its biases wander.
    #[default]
    Realistic,
    /// The published static model held at 25 degC with white noise only (an idealised part).
    Settled,
    /// As realistic, but a part drawn by the seed from the datasheet's spreads (offset, sensitivity,
    /// non-orthogonality and their drift), so that boards of different seeds differ as real ones do.
    Drawn,
}

/// A simulated sensor: the seed of its noise, its kind and its part.
pub type SensorChoice = (u64, SimSensor, SimPart);

/// Which power-on of a simulated board: the `cycle`-th (0: the first; each its own noise), with a
/// turn-on bias of standard deviation `turn_on_bias_g` (g) drawn at it.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PowerOn {
    pub cycle: u64,
    pub turn_on_bias_g: f32,
}

/// A running simulated board.
pub struct SimBoard {
    commands: Sender<SimCommand>,
    thread: Option<JoinHandle<SimFlash>>,
    truth: TrueErrors,
    /// How the truth moves with temperature (none for the settled sensor).
    drift: ThermalDrift,
    kind: SimSensor,
    now_us: Arc<AtomicU64>,
}

impl SimBoard {
    /// Boots a board on `flash` (keep it across `stop` and `spawn` to simulate a restart), with the
    /// published error model and noise seeded by `seed`, and serves `port` until stopped, its time
    /// fast-forwarded while it works; the realistic simulated sensor.
    pub fn spawn<P: Port + 'static>(port: P, flash: SimFlash, seed: u64) -> Self {
        Self::spawn_with(port, flash, seed, SimSensor::Realistic, Pace::Fast)
    }

    /// [`Self::spawn`] with the simulated sensor of the owner's choice and simulated time at `pace`.
    pub fn spawn_with<P: Port + 'static>(port: P, flash: SimFlash, seed: u64, kind: SimSensor, pace: Pace) -> Self {
        Self::spawn_part(port, flash, (seed, kind, SimPart::mpu6050()), pace)
    }

    /// [`Self::spawn_with`] with a simulated part of the owner's choice: `sensor` is the seed, the
    /// kind of sensor and the part.
    pub fn spawn_part<P: Port + 'static>(port: P, flash: SimFlash, sensor: SensorChoice, pace: Pace) -> Self {
        Self::spawn_powered(port, flash, sensor, PowerOn::default(), pace)
    }

    /// [`Self::spawn_part`] at a given power-on of the same board (`accelcal repeat`).
    pub fn spawn_powered<P: Port + 'static>(
        port: P,
        flash: SimFlash,
        sensor: SensorChoice,
        power: PowerOn,
        pace: Pace,
    ) -> Self {
        let (seed, kind, part) = sensor;
        let mut sensor = match kind {
            SimSensor::Realistic | SimSensor::Drawn => SimMpu6050::new(seed),
            SimSensor::Settled => SimMpu6050::settled(seed),
        }
        .with_part(part);
        if kind == SimSensor::Drawn {
            sensor.physics.drawn_part(seed);
        }
        sensor.physics.power_on(power.cycle, power.turn_on_bias_g);
        let (truth, drift) = (sensor.physics.truth, sensor.physics.drift);
        let (commands, inbox) = channel();
        let now_us = Arc::new(AtomicU64::new(0));
        let clock = now_us.clone();
        let thread = std::thread::spawn(move || {
            // NOTE: boot fails only for a flash range that does not fit the flash, and
            // SIM_FLASH_RANGE is the whole of SimFlash; the board then simply never answers.
            match block_on(Device::boot(sensor, flash, SIM_FLASH_RANGE, sim_serial_number(seed))) {
                Ok(device) => serve(port, Server::new(device), inbox, pace, clock),
                Err(_) => SimFlash::default(),
            }
        });
        SimBoard { commands, thread: Some(thread), truth, drift, kind, now_us }
    }

    /// A fresh simulated board in this process, behind an in-memory pipe, and a session with it; its
    /// clock runs in lockstep with the requests, so a run is repeatable by its seed.
    pub fn in_process(seed: u64, kind: SimSensor) -> Result<(Connection, SimBoard), LinkError> {
        Self::in_process_part((seed, kind, SimPart::mpu6050()))
    }

    /// [`Self::in_process`] with a simulated part of the owner's choice.
    pub fn in_process_part(sensor: SensorChoice) -> Result<(Connection, SimBoard), LinkError> {
        Self::in_process_powered(sensor, PowerOn::default())
    }

    /// [`Self::in_process_part`] at a given power-on of the same board.
    pub fn in_process_powered(sensor: SensorChoice, power: PowerOn) -> Result<(Connection, SimBoard), LinkError> {
        let (host_end, device_end) = pipe();
        let board = SimBoard::spawn_powered(device_end, SimFlash::new(), sensor, power, Pace::Lockstep);
        Ok((Connection::over(Box::new(host_end))?, board))
    }

    /// Collects `how`'s simulated session on this board over `connection` (the core's
    /// `SimulatedSession::collect`, each request blocking on the pipe).
    pub fn collect_session(
        &self,
        how: &SimulatedSession,
        connection: &mut Connection,
    ) -> Result<Session, ProcedureError> {
        let link = connection.client.link();
        let (controls, clock) = (Box::new(self.controls()), Arc::new(self.clock()));
        block_on(how.collect(SimulatedBoard { link, info: &connection.info, controls, clock }))
    }

    /// A handle that turns the board: for the procedure's simulated hand, and for tests.
    pub fn controls(&self) -> Sender<SimCommand> {
        self.commands.clone()
    }

    /// A reader of the simulated time since power-on, in seconds (it moves while the board serves).
    pub fn clock(&self) -> impl Fn() -> f64 + Send + Sync + 'static {
        let now_us = self.now_us.clone();
        move || now_us.load(Ordering::Relaxed) as f64 * 1e-6
    }

    /// The simulated sensor's true errors at 25 degC (its true static calibration).
    pub fn truth(&self) -> TrueErrors {
        self.truth
    }

    /// The simulated sensor's true errors when its TEMP_OUT reads `reading_c` degC (the settled
    /// sensor's are the same at every temperature).
    pub fn truth_at(&self, reading_c: f32) -> TrueErrors {
        let environment = Physics::new(0).environment;
        match self.kind {
            SimSensor::Realistic | SimSensor::Drawn => {
                self.drift.at(&self.truth, reading_c - environment.reading_offset_c)
            }
            SimSensor::Settled => self.truth,
        }
    }

    /// The true error of `calibration` at TEMP_OUT `reading_c` degC: the rms of | |a| - 1 g |, in
    /// mg, over [`TRUE_ERROR_ORIENTATIONS`] orientations evenly over the sphere (a Fibonacci lattice),
    /// each this sensor's noise-free reading there corrected as the chip corrects it at that temperature.
    pub fn true_error_mg(&self, calibration: &Calibration, reading_c: f32) -> f64 {
        let truth = self.truth_at(reading_c);
        let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
        let count = TRUE_ERROR_ORIENTATIONS;
        let squares: f64 = (0..count)
            .map(|i| {
                let z = 1.0 - 2.0 * (i as f64 + 0.5) / count as f64;
                let (r, angle) = ((1.0 - z * z).sqrt(), golden * i as f64);
                let up = [(r * angle.cos()) as f32, (r * angle.sin()) as f32, z as f32];
                let corrected = calibration.apply_at(truth.reading_g(up), reading_c);
                ((f64::from(shared::linalg::norm(corrected)) - 1.0) * 1000.0).powi(2)
            })
            .sum();
        (squares / count as f64).sqrt()
    }

    /// The truth at TEMP_OUT `reading_c` degC for a report, with the realistic sensor's drift.
    pub fn truth_json(&self, reading_c: f32) -> TruthJson {
        let reading_offset_c = Physics::new(0).environment.reading_offset_c;
        let drift = match self.kind {
            SimSensor::Realistic | SimSensor::Drawn => {
                Some(super::truth::drift_json(&self.truth, &self.drift, TRUTH_REF_TEMP_C, reading_offset_c))
            }
            SimSensor::Settled => None,
        };
        super::truth::truth_json(reading_c, &self.truth_at(reading_c), drift)
    }

    /// The surroundings, in degC, in which the settled sensor reports `reading_c`.
    pub fn ambient_for(&self, reading_c: f32) -> f32 {
        let environment = Physics::new(0).environment;
        match self.kind {
            SimSensor::Realistic | SimSensor::Drawn => {
                reading_c - environment.reading_offset_c - environment.self_heating_c
            }
            SimSensor::Settled => reading_c,
        }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::limits::DEFAULT_TARGET_MG;

    #[test]
    fn the_board_in_this_process_and_the_threaded_board_give_one_calibration_bit_for_bit() {
        let how = SimulatedSession { placement_deg: 3.0, hand_seed: 11, target_mg: DEFAULT_TARGET_MG };
        let (mut connection, board) = SimBoard::in_process(11, SimSensor::Realistic).unwrap();
        let threaded = board.collect_session(&how, &mut connection).unwrap();
        let in_process = how.in_process(11).unwrap();
        let config = connection.info.config;
        let calibration = |session: &Session| session.outcome(config).unwrap().calibration;
        assert!(threaded.captures.len() >= 11, "{} captures", threaded.captures.len());
        assert_eq!(threaded.captures.len(), in_process.captures.len());
        assert_eq!(calibration(&threaded), calibration(&in_process));
    }
}
