//! `accelcal sim --pty`: the simulated board on a pseudo-terminal, turned by lines on stdin.

use std::io::{BufRead, Write};
use std::sync::mpsc::Sender;

use firmware::sim::SimFlash;

use super::board::{SimBoard, SimCommand};

/// Why the pseudo-terminal server could not start.
#[derive(Debug, thiserror::Error)]
pub enum SimError {
    #[error("cannot create a pseudo-terminal: {reason}; run it on Linux or macOS, or use --sim in each command")]
    Pty { reason: String },
    #[error("the pseudo-terminal has no name; use --sim in each command instead")]
    Unnamed,
}

/// The commands stdin takes, for the message on an unknown one.
const USAGE: &str = "use place X Y Z, place +X, disconnect, connect";

/// Serves a simulated board on a pseudo-terminal until killed; prints the path first. Lines on
/// stdin turn the board: `place X Y Z`, `place +X`, `disconnect`, `connect`.
pub fn serve_pty(seed: u64) -> Result<(), SimError> {
    let (master, slave) = serialport::TTYPort::pair().map_err(|e| SimError::Pty { reason: e.to_string() })?;
    let path = serialport::SerialPort::name(&slave).ok_or(SimError::Unnamed)?;
    let board = SimBoard::spawn(master, SimFlash::new(), seed);
    println!("{path}");
    let _ = std::io::stdout().flush();
    obey_stdin(&board.controls());
    // NOTE: keep the slave end open: with no open slave, reads on the master fail.
    let _keep_open = slave;
    loop {
        std::thread::park();
    }
}

fn obey_stdin(controls: &Sender<SimCommand>) {
    for line in std::io::stdin().lock().lines().map_while(Result::ok) {
        match parse_command(&line) {
            Some(command) => {
                let _ = controls.send(command);
            }
            None => eprintln!("unknown command {line:?}: {USAGE}"),
        }
    }
}

fn parse_command(line: &str) -> Option<SimCommand> {
    let words: Vec<&str> = line.split_whitespace().collect();
    match words.as_slice() {
        ["place", face] => shared::Position::ALL
            .iter()
            .find(|p| p.name().eq_ignore_ascii_case(face))
            .map(|p| SimCommand::Place(p.specific_force_g())),
        ["place", x, y, z] => Some(SimCommand::Place([x.parse().ok()?, y.parse().ok()?, z.parse().ok()?])),
        ["disconnect"] => Some(SimCommand::Connect(false)),
        ["connect"] => Some(SimCommand::Connect(true)),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stdin_lines_become_board_commands() {
        assert_eq!(parse_command("place -y"), Some(SimCommand::Place([0.0, -1.0, 0.0])));
        assert_eq!(parse_command("place 0.5 0 -1"), Some(SimCommand::Place([0.5, 0.0, -1.0])));
        assert_eq!(parse_command("disconnect"), Some(SimCommand::Connect(false)));
        assert_eq!(parse_command("place sideways"), None);
    }
}
