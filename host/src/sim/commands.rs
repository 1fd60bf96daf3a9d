//! The lines `accelcal sim --pty` takes on stdin, and the help that lists them.

use firmware::sim::physics::Motion;

use accelcal_core::sim::SimCommand;

/// Every command stdin takes: how to write it, and what it does.
pub(super) const COMMANDS: &[(&str, &str)] = &[
    ("help", "list these commands"),
    (
        "turn +X|-X|+Y|-Y|+Z|-Z",
        "turn the board by hand, from where it rests, to rest with that axis up (the gyro sees it)",
    ),
    ("turn +X+Y+Z|...|-X-Y-Z", "turn it by hand to rest on that corner"),
    ("rotate x|y|z DEG", "turn it by hand DEG degrees about its own x, y or z axis (-360 to 360)"),
    (
        "tip DEG",
        "tip it by hand over an edge, DEG degrees about a horizontal line (the gyro check's quarter turn: tip 90)",
    ),
    (
        "place +X|...|-Z|+X+Y+Z|...",
        "put the board down at once with that axis or corner up (no turn: the gyro sees none)",
    ),
    ("place X Y Z", "put it down at once with the body direction (X, Y, Z) up"),
    ("tilt DEG", "tilt the board by DEG degrees about its x axis (over a second) and leave it there"),
    (
        "turn SECONDS [DEG_PER_S]",
        "turn the board about its x axis (default 10 deg/s, at most 250) for SECONDS, then rest",
    ),
    ("shake SECONDS [G]", "shake the board along x (default 0.05 g at 5 Hz, at most 1 g) for SECONDS"),
    ("restart", "reboot the board: what is in RAM is lost, the stored calibration stays"),
    ("unplug", "disconnect the sensor from the bus, as a loose wire (also: disconnect)"),
    ("replug", "connect the sensor again (also: connect)"),
    ("lose N", "the link loses the next N streamed samples, as a flaky cable"),
    ("ambient C [C_PER_S]", "move the surroundings to C degC (-40 to 85; at once, or at up to 10 degC per second)"),
];

/// Turn rate of `turn` without a rate, in deg/s.
const DEFAULT_TURN_DPS: f32 = 10.0;
/// Fastest turn, in deg/s: the gyro's full scale at its default range (Product Specification 6.1, FS_SEL 0).
const MAX_TURN_DPS: f32 = 250.0;
/// Longest timed motion, in seconds.
const MAX_MOTION_S: f32 = 600.0;
/// Amplitude of `shake` without one, in g, its largest, and its frequency in Hz.
const DEFAULT_SHAKE_G: f32 = 0.05;
const MAX_SHAKE_G: f32 = 1.0;
const SHAKE_HZ: f32 = 5.0;
/// The surroundings the sensor works in, in degC (Product Specification 6.1: operating range).
const AMBIENT_RANGE_C: (f32, f32) = (-40.0, 85.0);
/// Fastest change of the surroundings, in degC/s (faster than any oven; `ambient C` alone is at once).
const MAX_AMBIENT_C_PER_S: f32 = 10.0;
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

/// The command a line asks for, or why it is refused (not a command, or a value the board cannot meet).
pub(super) fn parse(line: &str) -> Result<Line, String> {
    let words: Vec<&str> = line.split_whitespace().collect();
    let command = match words.as_slice() {
        ["help"] => return Ok(Line::Help),
        ["turn", face] if face.starts_with(['+', '-']) && face.len() > 1 => SimCommand::TurnTo(face_up(face)?),
        ["rotate", axis, degrees] => rotation_by(axis, number(degrees, -360.0, 360.0)?)?,
        ["tip", degrees] => SimCommand::Tip(number(degrees, -360.0, 360.0)?),
        ["place", face] => SimCommand::Place(face_up(face)?),
        ["place", x, y, z] => SimCommand::Place(direction([x, y, z])?),
        ["tilt", degrees] => timed(rotation(number(degrees, -360.0, 360.0)?), 1.0),
        ["turn", seconds] => timed(rotation(DEFAULT_TURN_DPS), seconds_of(seconds)?),
        ["turn", seconds, rate] => timed(rotation(number(rate, -MAX_TURN_DPS, MAX_TURN_DPS)?), seconds_of(seconds)?),
        ["shake", seconds] => timed(shaking(DEFAULT_SHAKE_G), seconds_of(seconds)?),
        ["shake", seconds, amplitude] => timed(shaking(number(amplitude, 0.0, MAX_SHAKE_G)?), seconds_of(seconds)?),
        ["restart"] => SimCommand::Restart,
        ["unplug" | "disconnect"] => SimCommand::Connect(false),
        ["replug" | "connect"] => SimCommand::Connect(true),
        ["lose", count] => SimCommand::LoseSamples(count.parse().map_err(|_| format!("{count:?} is not a count"))?),
        ["ambient", target] => ambient(target, None)?,
        ["ambient", target, rate] => ambient(target, Some(rate))?,
        _ => return Err(format!("unknown command {line:?}")),
    };
    Ok(Line::Board(command))
}

/// The help text: one line per command.
pub(super) fn help() -> String {
    let width = COMMANDS.iter().map(|(usage, _)| usage.len()).max().unwrap_or(0);
    COMMANDS.iter().map(|(usage, what)| format!("  {usage:width$}  {what}\n")).collect()
}

/// A number within `low`-`high`, or why not (nan and infinities are not numbers here).
fn number(text: &str, low: f32, high: f32) -> Result<f32, String> {
    match text.parse::<f32>() {
        Ok(value) if value.is_nan() => Err(format!("{text:?} is not a number")),
        Ok(value) if (low..=high).contains(&value) => Ok(value),
        Ok(value) => Err(format!("{value} is not in {low} to {high}")),
        Err(_) => Err(format!("{text:?} is not a number")),
    }
}

fn seconds_of(text: &str) -> Result<f32, String> {
    number(text, f32::MIN_POSITIVE, MAX_MOTION_S)
}

/// A body direction of any length but not zero.
fn direction(texts: [&&str; 3]) -> Result<[f32; 3], String> {
    let [x, y, z] = texts.map(|t| number(t, -1e3, 1e3));
    let up = [x?, y?, z?];
    match up.iter().any(|v| *v != 0.0) {
        true => Ok(up),
        false => Err("0 0 0 is no direction".to_owned()),
    }
}

/// A face or a corner by name, as `calibrate` asks for it.
fn face_up(name: &str) -> Result<[f32; 3], String> {
    crate::orientation::Orientation::named(name)
        .map(|o| o.up.map(|v| v as f32))
        .ok_or_else(|| format!("{name:?} is no face (+X ... -Z) or corner (+X+Y+Z ... -X-Y-Z)"))
}

/// A hand's turn by `degrees` about the board's own `axis` (x, y or z).
fn rotation_by(axis: &str, degrees: f32) -> Result<SimCommand, String> {
    let axis = match axis.to_ascii_lowercase().as_str() {
        "x" => [1.0, 0.0, 0.0],
        "y" => [0.0, 1.0, 0.0],
        "z" => [0.0, 0.0, 1.0],
        other => return Err(format!("{other:?} is no axis: x, y or z")),
    };
    Ok(crate::sim::turn::turning(axis, f64::from(degrees)))
}

fn rotation(rate_dps: f32) -> Motion {
    Motion::Rotating { axis: X_AXIS, rate_dps }
}

fn shaking(amplitude_g: f32) -> Motion {
    Motion::Vibrating { amplitude_g, frequency_hz: SHAKE_HZ }
}

/// The surroundings moving to `target` degC at `rate` degC/s (at once without one).
fn ambient(target: &str, rate: Option<&&str>) -> Result<SimCommand, String> {
    let target_c = number(target, AMBIENT_RANGE_C.0, AMBIENT_RANGE_C.1)?;
    let c_per_s = rate.map_or(Ok(f32::INFINITY), |r| number(r, f32::MIN_POSITIVE, MAX_AMBIENT_C_PER_S))?;
    Ok(SimCommand::Ambient { target_c, c_per_s })
}

/// `motion` for `seconds`, then rest.
fn timed(motion: Motion, seconds: f32) -> SimCommand {
    SimCommand::MoveFor { motion, seconds }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn board(line: &str) -> Option<SimCommand> {
        match parse(line).ok()? {
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
        assert_eq!(parse("help"), Ok(Line::Help));
        assert!(parse("place sideways").is_err());
        assert!(parse("turn -3").is_err());
    }

    #[test]
    fn a_person_turns_the_board_by_hand_to_a_face_or_about_any_of_its_axes() {
        assert_eq!(board("turn -Y"), Some(SimCommand::TurnTo([0.0, -1.0, 0.0])));
        assert_eq!(board("tip 90"), Some(SimCommand::Tip(90.0)));
        assert_eq!(board("turn +x+y+z").map(|c| matches!(c, SimCommand::TurnTo(_))), Some(true));
        let Some(SimCommand::MoveFor { motion: Motion::Turning { axis, angle_deg, seconds }, .. }) =
            board("rotate y -90")
        else {
            panic!("rotate y -90 is no turn: {:?}", parse("rotate y -90"));
        };
        // A quarter turn at a hand's pace: 0.6 s plus 90 / 150 s, about -y (the negative angle).
        assert_eq!((axis, angle_deg), ([0.0, -1.0, 0.0], 90.0));
        assert!((seconds - 1.2).abs() < 1e-6, "{seconds}");
    }

    #[test]
    fn values_the_board_or_sensor_cannot_meet_are_refused_with_the_reason() {
        for (line, reason) in [
            ("place nan 0 0", "\"nan\" is not a number"),
            ("place 0 0 0", "no direction"),
            ("ambient 1e6", "not in -40 to 85"),
            ("ambient -300", "not in -40 to 85"),
            ("ambient 20 inf", "not in"),
            ("turn 5 1e9", "not in -250 to 250"),
            ("shake 1 5", "not in 0 to 1"),
            ("rotate w 90", "no axis"),
            ("turn +W", "no face"),
        ] {
            let error = parse(line).unwrap_err();
            assert!(error.contains(reason), "{line}: {error}");
        }
    }

    #[test]
    fn help_lists_every_command_the_parser_takes() {
        let text = help();
        for word in
            ["help", "place", "tilt", "turn", "rotate", "shake", "restart", "unplug", "replug", "lose", "ambient"]
        {
            assert!(text.lines().any(|l| l.trim_start().starts_with(word)), "{word} missing from\n{text}");
        }
        for line in [
            "turn +Z",
            "rotate x 45",
            "place +X",
            "place 0 0 1",
            "tilt 5",
            "turn 1 20",
            "shake 1",
            "lose 2",
            "ambient 30 0.5",
        ] {
            assert!(parse(line).is_ok(), "{line}");
        }
    }
}
