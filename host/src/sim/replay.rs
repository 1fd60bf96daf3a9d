//! `accelcal sim --sketch NAME --pty`: a board running someone's own sketch, on a pseudo-terminal:
//! it prints a simulated person's session line by line at the sketch's own pace, never waits to be
//! asked, counts every byte written to it, and stops its program on 0x03 (Ctrl-C), as MicroPython
//! does.

use std::io::{Read, Write};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use serialport::TTYPort;

use super::person::PersonSession;
use super::pty::SimError;
use super::sketch::{Sketch, TimedLine};

/// What a replay shares with whoever watches it.
#[derive(Debug, Clone, Default)]
pub struct ReplayState {
    /// Bytes written to the board.
    pub written: Arc<AtomicUsize>,
    /// The program was stopped by a 0x03.
    pub stopped: Arc<AtomicBool>,
    /// Lines printed so far.
    pub printed: Arc<AtomicUsize>,
}

/// A replay running on a pseudo-terminal.
pub struct Replay {
    /// The path to open.
    pub path: String,
    /// What it has seen and done.
    pub state: ReplayState,
    /// The lines it prints, with their times.
    pub lines: Vec<TimedLine>,
    _slave: TTYPort,
}

impl Replay {
    /// Starts printing person `seed`'s session as `sketch` does, `speed` times its own pace.
    pub fn spawn(sketch: Sketch, seed: u64, speed: f64) -> Result<Replay, SimError> {
        let (master, slave) = TTYPort::pair().map_err(|e| SimError::Pty { reason: e.to_string() })?;
        let path = serialport::SerialPort::name(&slave).ok_or(SimError::Unnamed)?;
        let reader = master.try_clone_native().map_err(|e| SimError::Pty { reason: e.to_string() })?;
        let lines = sketch.lines(&PersonSession::new(seed, sketch.reading()));
        let state = ReplayState::default();
        let (printing, listening) = (state.clone(), state.clone());
        let to_print = lines.clone();
        std::thread::spawn(move || print_lines(master, &to_print, speed, &printing));
        std::thread::spawn(move || count_written(reader, &listening));
        Ok(Replay { path, state, lines, _slave: slave })
    }
}

/// How long a write may wait for the reader: a board's USB serial waits while the host does not
/// read (a busy host), and goes on once it does.
const WRITE_WAIT: Duration = Duration::from_secs(60);

fn print_lines(mut master: TTYPort, lines: &[TimedLine], speed: f64, state: &ReplayState) {
    // NOTE: with the pair's short default timeout a write gave up while the reader was busy for a
    // moment, and the replay stopped printing for good (a stream taken for stopped under load).
    let _ = serialport::SerialPort::set_timeout(&mut master, WRITE_WAIT);
    let start = Instant::now();
    for line in lines {
        let due = Duration::from_secs_f64(line.at_s / speed);
        std::thread::sleep(due.saturating_sub(start.elapsed()));
        if state.stopped.load(Ordering::SeqCst) || master.write_all(line.text.as_bytes()).is_err() {
            return;
        }
        state.printed.fetch_add(1, Ordering::SeqCst);
    }
}

fn count_written(mut reader: TTYPort, state: &ReplayState) {
    let _ = serialport::SerialPort::set_timeout(&mut reader, Duration::from_millis(200));
    let mut buffer = [0u8; 256];
    loop {
        match reader.read(&mut buffer) {
            Ok(n) if n > 0 => {
                state.written.fetch_add(n, Ordering::SeqCst);
                if buffer[..n].contains(&0x03) {
                    state.stopped.store(true, Ordering::SeqCst);
                }
            }
            Ok(_) => {}
            Err(e) if e.kind() == std::io::ErrorKind::TimedOut => {}
            Err(_) => std::thread::sleep(Duration::from_millis(50)),
        }
    }
}

/// Prints the whole log a person's session with `sketch` gives, at once, on stdout.
pub fn print_log(sketch: Sketch, seed: u64) -> std::io::Result<()> {
    let session = PersonSession::new(seed, sketch.reading());
    let mut out = std::io::stdout().lock();
    sketch.lines(&session).iter().try_for_each(|line| out.write_all(line.text.as_bytes()))
}

/// Serves the replay until killed, printing its path first and, on stderr, what was written to it.
pub fn serve_replay(sketch: Sketch, seed: u64) -> Result<(), SimError> {
    let replay = Replay::spawn(sketch, seed, 1.0)?;
    println!("{}", replay.path);
    let _ = std::io::stdout().flush();
    let minutes = replay.lines.last().map_or(0.0, |l| l.at_s) / 60.0;
    eprintln!(
        "{sketch:?} sketch on {}: a person's {minutes:.1}-minute session at the sketch's own pace; 0x03 stops it",
        replay.path
    );
    let mut reported = (0, false);
    loop {
        std::thread::sleep(Duration::from_millis(200));
        let now = (replay.state.written.load(Ordering::SeqCst), replay.state.stopped.load(Ordering::SeqCst));
        if now != reported {
            let stopped = if now.1 { "; its program stopped (0x03)" } else { "" };
            eprintln!("{} bytes were written to the board{stopped}", now.0);
            reported = now;
        }
    }
}
