//! Helpers of the tests that drive the real binary: a run with a time limit, and `accelcal sim --pty`.

// NOTE: each test binary uses a part of these helpers.
#![allow(dead_code)]

pub mod person;
pub mod side_by_side;
pub mod throwaway_postgres;

use std::io::{BufRead, Read};
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

/// Runs `accelcal` and waits at most `limit` for it; a run still going then is killed and fails the test.
pub fn accelcal_within(args: &[&str], limit: Duration) -> (Output, Duration) {
    let started = Instant::now();
    let mut child = Command::new(env!("CARGO_BIN_EXE_accelcal"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let stdout = read_in_background(child.stdout.take().unwrap());
    let stderr = read_in_background(child.stderr.take().unwrap());
    let status = wait_or_kill(&mut child, limit);
    let elapsed = started.elapsed();
    let output = Output { status, stdout: stdout.join().unwrap(), stderr: stderr.join().unwrap() };
    (output, elapsed)
}

fn read_in_background(mut pipe: impl Read + Send + 'static) -> std::thread::JoinHandle<Vec<u8>> {
    std::thread::spawn(move || {
        let mut bytes = Vec::new();
        let _ = pipe.read_to_end(&mut bytes);
        bytes
    })
}

pub fn wait_or_kill(child: &mut Child, limit: Duration) -> std::process::ExitStatus {
    let started = Instant::now();
    loop {
        if let Some(status) = child.try_wait().unwrap() {
            return status;
        }
        if started.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            panic!("accelcal still running after {limit:?}: it hangs");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// `accelcal sim --pty` running in the background, killed when dropped.
pub struct SimPty {
    child: Child,
    /// The pseudo-terminal's path.
    pub path: String,
}

impl SimPty {
    /// Starts `accelcal sim --pty` with `extra` arguments and reads its path.
    pub fn start(extra: &[&str]) -> Self {
        Self::with_seed("7", extra)
    }

    /// Starts `accelcal sim --pty --seed SEED` with `extra` arguments and reads its path.
    pub fn with_seed(seed: &str, extra: &[&str]) -> Self {
        let mut child = Command::new(env!("CARGO_BIN_EXE_accelcal"))
            .args(["sim", "--pty", "--seed", seed])
            .args(extra)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .spawn()
            .unwrap();
        let mut first_line = String::new();
        std::io::BufReader::new(child.stdout.take().unwrap()).read_line(&mut first_line).unwrap();
        SimPty { child, path: first_line.trim().to_owned() }
    }
}

impl SimPty {
    /// Writes one command line to the simulated board's stdin.
    pub fn tell(&mut self, line: &str) {
        use std::io::Write;
        let stdin = self.child.stdin.as_mut().unwrap();
        writeln!(stdin, "{line}").unwrap();
        stdin.flush().unwrap();
    }

    /// Writes one command line to the simulated board's stdin and gives it time to act.
    pub fn command(&mut self, line: &str) {
        self.tell(line);
        std::thread::sleep(Duration::from_millis(200));
    }
}

impl Drop for SimPty {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// The real Pico binary (dist/accelcal-pico.uf2) under `accelcal sim --pty --pico`, killed when
/// dropped; its path is read once the emulated board's USB port is open.
pub struct EmulatedPico {
    child: Child,
    lines: std::sync::mpsc::Receiver<String>,
    /// The pseudo-terminal's path (a new one after each `cable in`).
    pub path: String,
}

impl EmulatedPico {
    /// Boots the binary with the realistic simulated sensor of `seed`; waits at most 60 s for its port.
    pub fn boot(seed: &str) -> Self {
        let uf2 = concat!(env!("CARGO_MANIFEST_DIR"), "/../dist/accelcal-pico.uf2");
        let mut child = Command::new(env!("CARGO_BIN_EXE_accelcal"))
            .args(["sim", "--pty", "--seed", seed, "--pico", uf2])
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .spawn()
            .unwrap();
        let (send, lines) = std::sync::mpsc::channel();
        let stdout = std::io::BufReader::new(child.stdout.take().unwrap());
        std::thread::spawn(move || stdout.lines().map_while(Result::ok).for_each(|line| drop(send.send(line))));
        let mut pico = EmulatedPico { child, lines, path: String::new() };
        pico.path = pico.next_path();
        pico
    }

    /// The next path the bridge prints (the port after boot or after the cable is plugged in).
    pub fn next_path(&mut self) -> String {
        let line = self.lines.recv_timeout(Duration::from_secs(60));
        line.expect("the emulated Pico opened no USB port within 60 s (see its stderr)")
    }

    /// Writes one command line to the bridge's stdin.
    pub fn tell(&mut self, line: &str) {
        use std::io::Write;
        let stdin = self.child.stdin.as_mut().unwrap();
        writeln!(stdin, "{line}").unwrap();
        stdin.flush().unwrap();
    }
}

impl Drop for EmulatedPico {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}
