//! The line protocol with the emulator process (`boards/pico/emulator/harness.mjs`, whose header
//! lists the lines): what the emulated chip did, and the answers it waits for.

use std::io::{BufRead, BufReader, Write};
use std::path::Path;
use std::process::{Child, ChildStdin, ChildStdout, Command, Stdio};

use super::EmulatorError;

/// One thing the emulated chip did.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Event {
    /// An I2C transaction starts at this emulated time, in nanoseconds.
    Start { at_ns: u64 },
    /// A repeated start within a transaction.
    RepeatedStart,
    /// The chip addresses a target, to read or to write; answer with [`Harness::acknowledge`].
    Address { address: u8, read: bool },
    /// The chip writes a byte.
    Write(u8),
    /// The chip reads a byte; answer with [`Harness::byte`].
    Read,
    /// The transaction ends.
    Stop,
    /// The device sent these bytes over USB.
    FromDevice(Vec<u8>),
    /// The USB serial port exists (the device is enumerated and configured).
    Open,
    /// A poll at this emulated time, after this many executed CPU cycles; answer with
    /// [`Harness::answer_poll`].
    Poll { at_ns: u64, cycles: u64 },
}

/// What the bridge tells the chip at a poll.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Control {
    /// Bytes from the host for the device's USB OUT endpoint.
    ToDevice(Vec<u8>),
    /// A power cycle: the chip restarts from its flash.
    PowerCycle,
    /// The USB cable plugged in (true) or pulled (false).
    Cable(bool),
    /// A program on the host opened (true) or closed (false) the port: DTR rises or falls.
    Port(bool),
}

/// The emulator process and its two pipes.
pub(super) struct Harness {
    child: Child,
    events: BufReader<ChildStdout>,
    answers: ChildStdin,
}

impl Harness {
    /// Starts `node harness.mjs UF2` in `dir`.
    pub(super) fn start(dir: &Path, uf2: &Path) -> Result<Self, EmulatorError> {
        let mut child = Command::new("node")
            .arg(dir.join("harness.mjs"))
            .arg(uf2)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .spawn()
            .map_err(|e| EmulatorError::Node(e.to_string()))?;
        let (Some(answers), Some(events)) = (child.stdin.take(), child.stdout.take()) else {
            return Err(EmulatorError::Node("no pipes to the emulator".into()));
        };
        Ok(Harness { child, events: BufReader::new(events), answers })
    }

    /// The next event; an error when the emulator ended (it says why on stderr).
    pub(super) fn next(&mut self) -> Result<Event, EmulatorError> {
        let mut line = String::new();
        match self.events.read_line(&mut line) {
            Ok(0) | Err(_) => Err(EmulatorError::Ended(self.child.wait().map(|s| s.to_string()).unwrap_or_default())),
            Ok(_) => parse(line.trim_end()).ok_or(EmulatorError::Garbled(line)),
        }
    }

    /// Answers an [`Event::Address`].
    pub(super) fn acknowledge(&mut self, acknowledged: bool) -> Result<(), EmulatorError> {
        self.say(&format!("a {}", u8::from(acknowledged)))
    }

    /// Answers an [`Event::Read`].
    pub(super) fn byte(&mut self, value: u8) -> Result<(), EmulatorError> {
        self.say(&format!("b {value}"))
    }

    /// Answers an [`Event::Poll`] with what the chip is to do before it runs on.
    pub(super) fn answer_poll(&mut self, controls: &[Control]) -> Result<(), EmulatorError> {
        let mut text = String::new();
        for control in controls {
            text += &match control {
                Control::ToDevice(bytes) => format!("h {}\n", hex(bytes)),
                Control::PowerCycle => "power\n".into(),
                Control::Cable(plugged) => format!("cable {}\n", u8::from(*plugged)),
                Control::Port(open) => format!("port {}\n", u8::from(*open)),
            };
        }
        self.say(&(text + "."))
    }

    fn say(&mut self, text: &str) -> Result<(), EmulatorError> {
        writeln!(self.answers, "{text}")
            .and_then(|()| self.answers.flush())
            .map_err(|e| EmulatorError::Node(e.to_string()))
    }
}

impl Drop for Harness {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// One event line, or `None` when it is not one.
fn parse(line: &str) -> Option<Event> {
    let words: Vec<&str> = line.split(' ').collect();
    Some(match words.as_slice() {
        ["s", at] => Event::Start { at_ns: at.parse().ok()? },
        ["S"] => Event::RepeatedStart,
        ["c", address, mode] => Event::Address { address: address.parse().ok()?, read: *mode == "1" },
        ["w", value] => Event::Write(value.parse().ok()?),
        ["r"] => Event::Read,
        ["p"] => Event::Stop,
        ["u", bytes] => Event::FromDevice(unhex(bytes)?),
        ["open"] => Event::Open,
        ["t", at, cycles] => Event::Poll { at_ns: at.parse().ok()?, cycles: cycles.parse().ok()? },
        _ => return None,
    })
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

fn unhex(text: &str) -> Option<Vec<u8>> {
    (0..text.len()).step_by(2).map(|i| u8::from_str_radix(text.get(i..i + 2)?, 16).ok()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_event_line_of_the_harness_parses_to_its_event() {
        assert_eq!(parse("s 454240"), Some(Event::Start { at_ns: 454_240 }));
        assert_eq!(parse("c 104 1"), Some(Event::Address { address: 0x68, read: true }));
        assert_eq!(parse("c 105 0"), Some(Event::Address { address: 0x69, read: false }));
        assert_eq!(parse("w 117"), Some(Event::Write(0x75)));
        assert_eq!(parse("u 00ff10"), Some(Event::FromDevice(vec![0, 255, 16])));
        assert_eq!(parse("t 2000000040 1126270"), Some(Event::Poll { at_ns: 2_000_000_040, cycles: 1_126_270 }));
        assert_eq!(parse("u 0f1"), None, "an odd number of hex digits");
        assert_eq!(parse("ready"), None);
        assert_eq!(hex(&[0, 0xab, 7]), "00ab07");
    }
}
