//! The lines `accelcal sim --pty` takes on stdin, and the help that lists them.

use firmware::sim::physics::Motion;

use super::board::SimCommand;

/// Every command stdin takes: how to write it, and what it does.
pub(super) const COMMANDS: &[(&str, &str)] = &[
    ("help", "list these commands"),
    ("place +X|-X|+Y|-Y|+Z|-Z", "rest the board with that axis up"),
    ("place +X+Y+Z|...|-X-Y-Z", "rest the board on that corner (the three axes 54.7 degrees from up)"),
    ("place X Y Z", "rest the board with the body direction (X, Y, Z) up"),
    ("tilt DEG", "tilt the board by DEG degrees about its x axis (over a second) and leave it there"),
    ("turn SECONDS [DEG_PER_S]", "turn the board about its x axis (default 10 deg/s) for SECONDS, then rest"),
    ("shake SECONDS [G]", "shake the board along x (default 0.05 g at 5 Hz, a hand's tremor) for SECONDS"),
    ("restart", "reboot the board: what is in RAM is lost, the stored calibration stays"),
    ("unplug", "disconnect the sensor from the bus, as a loose wire (also: disconnect)"),
    ("replug", "connect the sensor again (also: connect)"),
    ("lose N", "the link loses the next N streamed samples, as a flaky cable"),
    ("ambient C [C_PER_S]", "move the surroundings to C degC (at once, or at C_PER_S degC per second)"),
];

/// Turn rate of `turn` without a rate, in deg/s.
const DEFAULT_TURN_DPS: f32 = 10.0;
/// Amplitude of `shake` without one, in g, and its frequency in Hz.
const DEFAULT_SHAKE_G: f32 = 0.05;
const SHAKE_HZ: f32 = 5.0;
/// The axis turns and tilts go about: the board's x axis.
const X_AXIS: [f32; 3] = [1.0, 0.0, 0.0];

/// What a line on stdin asks for.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Line {
    /// List the commands.
    Help,
    /// Do this to the board.
    Board(SimCommand),
}

/// The command a line asks for; `None` for a line that is not one.
pub(super) fn parse(line: &str) -> Option<Line> {
    let words: Vec<&str> = line.split_whitespace().collect();
    let command = match words.as_slice() {
        ["help"] => return Some(Line::Help),
        ["place", face] => SimCommand::Place(face_up(face)?),
        ["place", x, y, z] => SimCommand::Place([x.parse().ok()?, y.parse().ok()?, z.parse().ok()?]),
        ["tilt", degrees] => timed(rotation(degrees.parse().ok()?), "1")?,
        ["turn", seconds] => timed(rotation(DEFAULT_TURN_DPS), seconds)?,
        ["turn", seconds, rate] => timed(rotation(rate.parse().ok()?), seconds)?,
        ["shake", seconds] => timed(shaking(DEFAULT_SHAKE_G), seconds)?,
        ["shake", seconds, amplitude] => timed(shaking(amplitude.parse().ok()?), seconds)?,
        ["restart"] => SimCommand::Restart,
        ["unplug" | "disconnect"] => SimCommand::Connect(false),
        ["replug" | "connect"] => SimCommand::Connect(true),
        ["lose", count] => SimCommand::LoseSamples(count.parse().ok()?),
        ["ambient", target] => ambient(target, "inf")?,
        ["ambient", target, rate] => ambient(target, rate)?,
        _ => return None,
    };
    Some(Line::Board(command))
}

/// The help text: one line per command.
pub(super) fn help() -> String {
    let width = COMMANDS.iter().map(|(usage, _)| usage.len()).max().unwrap_or(0);
    COMMANDS.iter().map(|(usage, what)| format!("  {usage:width$}  {what}\n")).collect()
}

/// A face or a corner by name, as `calibrate` asks for it.
fn face_up(name: &str) -> Option<[f32; 3]> {
    crate::orientation::Orientation::named(name).map(|o| o.up.map(|v| v as f32))
}

fn rotation(rate_dps: f32) -> Motion {
    Motion::Rotating { axis: X_AXIS, rate_dps }
}

fn shaking(amplitude_g: f32) -> Motion {
    Motion::Vibrating { amplitude_g, frequency_hz: SHAKE_HZ }
}

/// The surroundings moving to `target` degC at `rate` degC/s (a positive number, or `inf`: at once).
fn ambient(target: &str, rate: &str) -> Option<SimCommand> {
    let target_c: f32 = target.parse().ok().filter(|t: &f32| t.is_finite())?;
    let c_per_s: f32 = rate.parse().ok().filter(|r: &f32| *r > 0.0)?;
    Some(SimCommand::Ambient { target_c, c_per_s })
}

/// `motion` for `seconds` (a positive number), then rest.
fn timed(motion: Motion, seconds: &str) -> Option<SimCommand> {
    let seconds: f32 = seconds.parse().ok().filter(|s: &f32| s.is_finite() && *s > 0.0)?;
    Some(SimCommand::MoveFor { motion, seconds })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn board(line: &str) -> Option<SimCommand> {
        match parse(line)? {
            Line::Board(command) => Some(command),
            Line::Help => None,
        }
    }

    #[test]
    fn stdin_lines_become_board_commands() {
        assert_eq!(board("place -y"), Some(SimCommand::Place([0.0, -1.0, 0.0])));
        assert_eq!(board("place 0.5 0 -1"), Some(SimCommand::Place([0.5, 0.0, -1.0])));
        assert_eq!(board("tilt 30"), Some(SimCommand::MoveFor { motion: rotation(30.0), seconds: 1.0 }));
        assert_eq!(board("turn 4"), Some(SimCommand::MoveFor { motion: rotation(10.0), seconds: 4.0 }));
        assert_eq!(board("shake 2 0.2"), Some(SimCommand::MoveFor { motion: shaking(0.2), seconds: 2.0 }));
        assert_eq!(board("unplug"), Some(SimCommand::Connect(false)));
        assert_eq!(board("replug"), Some(SimCommand::Connect(true)));
        assert_eq!(board("restart"), Some(SimCommand::Restart));
        assert_eq!(board("lose 7"), Some(SimCommand::LoseSamples(7)));
        assert_eq!(board("ambient 40"), Some(SimCommand::Ambient { target_c: 40.0, c_per_s: f32::INFINITY }));
        assert_eq!(board("ambient 5 0.1"), Some(SimCommand::Ambient { target_c: 5.0, c_per_s: 0.1 }));
        assert_eq!(parse("ambient 5 -1"), None);
        assert_eq!(parse("help"), Some(Line::Help));
        assert_eq!(parse("place sideways"), None);
        assert_eq!(parse("turn -3"), None);
    }

    #[test]
    fn help_lists_every_command_the_parser_takes() {
        let text = help();
        for word in ["help", "place", "tilt", "turn", "shake", "restart", "unplug", "replug", "lose", "ambient"] {
            assert!(text.lines().any(|l| l.trim_start().starts_with(word)), "{word} missing from\n{text}");
            assert!(parse(word).is_some() || parse(&format!("{word} 1")).is_some() || word == "place", "{word}");
        }
    }
}
