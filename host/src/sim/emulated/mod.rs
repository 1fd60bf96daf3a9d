//! `accelcal sim --pty --pico FIRMWARE.uf2`: the real Pico binary, loaded from its UF2, run by the
//! rp2040js emulator (`boards/pico/emulator`), with this crate's simulated MPU-6050 on its I2C0 bus
//! and its USB serial port on a pseudo-terminal the unmodified host opens.
//!
//! The emulator reports every I2C event and polls this bridge each millisecond of emulated time;
//! the sensor's time is the emulated chip's, and the bridge holds the emulator to the wall clock, so
//! a person (or a test playing one) turns the board in real time, as with `sim --pty`.

mod error;
mod fit_timer;
mod harness;
mod port;

use std::io::{BufRead, Write};
use std::path::Path;
use std::sync::mpsc::{channel, Receiver};
use std::time::{Duration, Instant};

pub use error::EmulatorError;
use firmware::sim::{BytewiseTarget, SimMpu6050};
use fit_timer::FitTimer;
use harness::{Control, Event, Harness};
use port::HostPort;

use super::board::SimSensor;
use super::commands::{help, parse, Line};
use accelcal_core::sim::OwnerHand;
use accelcal_core::sim::SimCommand;

/// Where the emulator harness and its `node_modules` live in the repository.
const EMULATOR_DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../boards/pico/emulator");

/// What a line on stdin asks of the emulated board.
enum Order {
    Sensor(SimCommand),
    PowerCycle,
    Cable(bool),
}

/// The world around the emulated chip: its sensor, the person's hand, the USB port, the wall clock.
struct Bridge {
    sensor: SimMpu6050,
    hand: OwnerHand,
    bus: BytewiseTarget,
    port: HostPort,
    started: Instant,
    orders: Receiver<Order>,
    fits: FitTimer,
}

/// Serves the Pico binary `uf2` under the emulator until killed, with the simulated sensor of
/// `seed` and `kind`; prints the pseudo-terminal's path once the board's port is open (and again
/// after each `cable in`). Lines on stdin move the board as with `sim --pty`; `restart` is a power
/// cycle, `cable out` and `cable in` pull and plug the USB cable (which powers the Pico: a boot
/// from its flash when it is back).
pub fn serve_emulated(uf2: &Path, seed: u64, kind: SimSensor) -> Result<(), EmulatorError> {
    let dir = Path::new(EMULATOR_DIR);
    if !dir.join("node_modules/rp2040js").is_dir() {
        return Err(EmulatorError::NotInstalled(dir.to_path_buf()));
    }
    if !uf2.is_file() {
        return Err(EmulatorError::NoFirmware(uf2.to_path_buf()));
    }
    let mut sensor = match kind {
        SimSensor::Realistic | SimSensor::Drawn => SimMpu6050::new(seed),
        SimSensor::Settled => SimMpu6050::settled(seed),
    };
    if kind == SimSensor::Drawn {
        sensor.physics.drawn_part(seed);
    }
    let mut harness = Harness::start(dir, uf2)?;
    let (bus, hand, port, started) =
        (BytewiseTarget::default(), OwnerHand::default(), HostPort::plugged()?, Instant::now());
    let mut bridge = Bridge { sensor, hand, bus, port, started, orders: read_orders(), fits: FitTimer::default() };
    loop {
        let event = harness.next()?;
        bridge.handle(event, &mut harness)?;
    }
}

impl Bridge {
    fn handle(&mut self, event: Event, harness: &mut Harness) -> Result<(), EmulatorError> {
        match event {
            Event::Start { at_ns } => self.advance_to(at_ns),
            Event::Address { address, .. } => harness.acknowledge(self.bus.address(&mut self.sensor, address))?,
            Event::Write(value) => self.bus.write(&mut self.sensor, value),
            Event::Read => harness.byte(self.bus.read(&mut self.sensor))?,
            Event::RepeatedStart | Event::Stop => {}
            Event::FromDevice(bytes) => {
                self.fits.device_sent(&bytes);
                self.port.send(&bytes);
            }
            Event::Open => announce(self.port.path()),
            Event::Poll { at_ns, cycles } => {
                self.advance_to(at_ns);
                self.keep_to_the_wall_clock(at_ns);
                if let Some(line) = self.fits.poll(at_ns, cycles) {
                    eprintln!("{line}");
                }
                let controls = self.controls(at_ns, cycles)?;
                harness.answer_poll(&controls)?;
            }
        }
        Ok(())
    }

    /// Lets the sensor's time catch up with the emulated chip's.
    fn advance_to(&mut self, at_ns: u64) {
        let step_us = (at_ns / 1000).saturating_sub(self.sensor.now_us());
        self.hand.advance(&mut self.sensor, step_us);
    }

    /// Waits while the emulated chip is ahead of the wall clock (it falls behind while it computes).
    fn keep_to_the_wall_clock(&self, at_ns: u64) {
        let due = Duration::from_nanos(at_ns);
        if let Some(early) = due.checked_sub(self.started.elapsed()) {
            std::thread::sleep(early);
        }
    }

    /// What the chip is to do now: the person's orders, then what the host wrote.
    fn controls(&mut self, at_ns: u64, cycles: u64) -> Result<Vec<Control>, EmulatorError> {
        let mut controls = Vec::new();
        while let Ok(order) = self.orders.try_recv() {
            match order {
                Order::Sensor(command) => drop(self.hand.obey(&mut self.sensor, command)),
                Order::PowerCycle => controls.push(Control::PowerCycle),
                Order::Cable(plugged) => {
                    if plugged {
                        self.port.plug()?
                    } else {
                        self.port.pull()
                    }
                    controls.push(Control::Cable(plugged));
                }
            }
        }
        let (bytes, open) = self.port.take_written();
        // NOTE: the port's state before its bytes, so that what the host wrote reaches a device
        // that sees DTR high.
        controls.push(Control::Port(open));
        self.port.flush();
        if !bytes.is_empty() {
            self.fits.host_wrote(&bytes, at_ns, cycles);
            controls.push(Control::ToDevice(bytes));
        }
        Ok(controls)
    }
}

/// Prints the port's path for whoever started the bridge.
fn announce(path: Option<String>) {
    if let Some(path) = path {
        println!("{path}");
        let _ = std::io::stdout().flush();
        eprintln!("emulated Pico on {path}; type help for the commands that move it");
    }
}

/// Reads stdin on its own thread: each line an order, a refusal or the help.
fn read_orders() -> Receiver<Order> {
    let (send, orders) = channel();
    std::thread::spawn(move || {
        for line in std::io::stdin().lock().lines().map_while(Result::ok) {
            let order = match (line.trim(), parse(&line)) {
                ("cable out", _) => Order::Cable(false),
                ("cable in", _) => Order::Cable(true),
                (_, Ok(Line::Board(SimCommand::Restart))) => Order::PowerCycle,
                (_, Ok(Line::Board(command @ (SimCommand::LoseSamples(_) | SimCommand::Stop)))) => {
                    eprintln!("refused: {command:?} is not possible on the emulated board");
                    continue;
                }
                (_, Ok(Line::Board(command))) => Order::Sensor(command),
                (_, Ok(Line::Help)) => {
                    println!("{}cable out|cable in        pull or plug the USB cable", help());
                    continue;
                }
                ("", Err(_)) => continue,
                (_, Err(why)) => {
                    eprintln!("refused: {why} (help lists the commands)");
                    continue;
                }
            };
            if send.send(order).is_err() {
                break;
            }
        }
    });
    orders
}
