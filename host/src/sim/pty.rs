//! `accelcal sim --pty`: the simulated board on a pseudo-terminal, turned by lines on stdin.

use std::io::{BufRead, Write};
use std::sync::mpsc::Sender;

use firmware::sim::SimFlash;

use super::board::{SimBoard, SimSensor};
use super::clock::Pace;
use super::commands::{help, parse, Line};
use accelcal_core::sim::SimCommand;

/// Why the pseudo-terminal server could not start.
#[derive(Debug, thiserror::Error)]
pub enum SimError {
    #[error("cannot create a pseudo-terminal: {reason}; run it on Linux or macOS, or use --sim in each command")]
    Pty { reason: String },
    #[error("the pseudo-terminal has no name; use --sim in each command instead")]
    Unnamed,
}

/// Serves a simulated board on a pseudo-terminal until killed, its time running at `pace`; prints
/// the path first. Lines on stdin turn the board (`help` lists them).
pub fn serve_pty(seed: u64, pace: Pace) -> Result<(), SimError> {
    let (master, slave) = serialport::TTYPort::pair().map_err(|e| SimError::Pty { reason: e.to_string() })?;
    let path = serialport::SerialPort::name(&slave).ok_or(SimError::Unnamed)?;
    let board = SimBoard::spawn_with(master, SimFlash::new(), seed, SimSensor::Realistic, pace);
    println!("{path}");
    let _ = std::io::stdout().flush();
    let time = match pace {
        Pace::RealTime => "in real time",
        Pace::Fast => "fast-forwarded while it works",
        Pace::Lockstep => "fast-forwarded while it works, standing still while idle",
    };
    eprintln!("simulated board on {path}, {time}; type help for the commands that move it");
    obey_stdin(&board.controls());
    // NOTE: keep the slave end open: with no open slave, reads on the master fail.
    let _keep_open = slave;
    loop {
        std::thread::park();
    }
}

fn obey_stdin(controls: &Sender<SimCommand>) {
    for line in std::io::stdin().lock().lines().map_while(Result::ok) {
        match parse(&line) {
            Ok(Line::Board(command)) => {
                let _ = controls.send(command);
            }
            Ok(Line::Help) => print!("{}", help()),
            Err(_) if line.trim().is_empty() => {}
            Err(why) => eprintln!("refused: {why} (help lists the commands)"),
        }
        let _ = std::io::stdout().flush();
    }
}
