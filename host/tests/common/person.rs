//! A person at the board, played by a test: reads what `calibrate` tells the person on stderr and
//! turns the board through the stdin of `accelcal sim --pty` (or of the emulated Pico's bridge).

use std::io::BufRead;
use std::process::{Child, Command, Stdio};
use std::sync::mpsc::{channel, Receiver};
use std::time::Duration;

/// A board a person can move: takes `sim --pty`'s command lines.
pub trait Board {
    /// Writes one command line to the board's stdin.
    fn tell(&mut self, line: &str);
}

impl Board for super::SimPty {
    fn tell(&mut self, line: &str) {
        super::SimPty::tell(self, line)
    }
}

impl Board for super::EmulatedPico {
    fn tell(&mut self, line: &str) {
        super::EmulatedPico::tell(self, line)
    }
}

/// How the person moves the board to a wanted position.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Moves {
    /// Puts it down there at once (the gyro sees no turn).
    Place,
    /// Turns it there by hand (the gyro sees the turn; the verification's quarter turn too).
    Turn,
}

/// `accelcal calibrate` against a board, with its stderr lines on a channel.
pub struct Run {
    pub child: Child,
    lines: Receiver<String>,
    /// Every stderr line so far.
    pub seen: Vec<String>,
    moves: Moves,
}

impl Run {
    /// Starts `accelcal calibrate --port PORT ARGS`.
    pub fn start(port: &str, args: &[&str], moves: Moves) -> Self {
        Run::command(&[&["calibrate", "--port", port][..], args].concat(), moves)
    }

    /// Starts any `accelcal` command.
    pub fn command(args: &[&str], moves: Moves) -> Self {
        let mut child = Command::new(env!("CARGO_BIN_EXE_accelcal"))
            .args(args)
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        let (send, lines) = channel();
        let stderr = std::io::BufReader::new(child.stderr.take().unwrap());
        std::thread::spawn(move || stderr.lines().map_while(Result::ok).for_each(|line| drop(send.send(line))));
        Run { child, lines, seen: Vec::new(), moves }
    }

    /// Plays the person: moves the board as each instruction says, until a line contains `until`
    /// (or the run ends: `None`).
    pub fn follow(&mut self, board: &mut dyn Board, until: &str) -> Option<String> {
        // NOTE: midpoints of cube edges: 45 degrees from the faces and 35 from the corners the
        // calibration asked for, so each is fresh (limits::FRESH_DEG is 20).
        let fresh = ["place 0.707 0 0.707", "place 0 0.707 -0.707", "place -0.707 0.707 0"];
        let verb = if self.moves == Moves::Turn { "turn" } else { "place" };
        while let Ok(line) = self.lines.recv_timeout(Duration::from_secs(60)) {
            self.seen.push(line.clone());
            if let Some(rest) = line.strip_prefix("Rest the board with ") {
                board.tell(&format!("{verb} {}", rest.split_whitespace().next().unwrap()));
            } else if let Some(rest) = line.strip_prefix("Verification ") {
                let k: usize = rest.split(':').next().unwrap().parse().unwrap();
                board.tell(fresh[k - 1]);
            } else if line.starts_with("Now turn the board a quarter turn") {
                board.tell("tip 90");
            }
            if line.contains(until) {
                return Some(line);
            }
        }
        None
    }

    /// Every stderr line for `duration`, without moving the board.
    pub fn lines_for(&mut self, duration: Duration) -> Vec<String> {
        let end = std::time::Instant::now() + duration;
        let mut lines = Vec::new();
        while let Some(left) = end.checked_duration_since(std::time::Instant::now()) {
            match self.lines.recv_timeout(left) {
                Ok(line) => lines.push(line),
                Err(_) => break,
            }
        }
        self.seen.extend(lines.iter().cloned());
        lines
    }

    /// Sends Ctrl-C.
    pub fn interrupt(&self) {
        let status = Command::new("kill").args(["-INT", &self.child.id().to_string()]).status().unwrap();
        assert!(status.success());
    }

    /// Waits for the end; the exit status, stdout and every stderr line.
    pub fn finish(mut self, board: &mut dyn Board) -> (std::process::ExitStatus, String, String) {
        self.follow(board, "\u{0}never");
        let output = self.child.wait_with_output().unwrap();
        (output.status, String::from_utf8(output.stdout).unwrap(), self.seen.join("\n"))
    }
}
