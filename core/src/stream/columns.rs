//! Where time, the accelerometer and the gyro are in a stream's lines: by the names its header or
//! labels give them, else by how many values a line has (accelerometer before gyro, as every sketch
//! accelcal knows prints them; a first column that only grows is a clock).

use super::conventions::Dialect;
use super::line::Fields;
use super::StreamError;

/// The columns of one stream.
#[derive(Debug, Clone, PartialEq)]
pub struct Columns {
    /// The clock's column and its name, when there is one.
    pub time: Option<(usize, String)>,
    /// The accelerometer's x, y, z columns.
    pub accel: [usize; 3],
    /// The gyro's x, y, z columns, when the stream has a gyro.
    pub gyro: Option<[usize; 3]>,
}

/// Names of a clock column (lower case, `_` and spaces removed); `times` is `accelcal stream`'s `time_s`.
/// (`zeit`: German, as a European-locale logger heads it.)
const TIME_NAMES: [&str; 11] =
    ["millis", "ms", "time", "timestamp", "t", "micros", "us", "timems", "timeus", "times", "zeit"];
/// What accelerometer columns are called before their axis letter.
/// NOTE: a bare `x,y,z` (and `mx`, `raw_x`) is how accelcal's own data files name a reading.
const ACCEL_HEADS: [&str; 11] =
    ["a", "ac", "acc", "accel", "acceleration", "alpha", "accelerometer", "arss", "", "m", "raw"];
/// What gyro columns are called before their axis letter.
const GYRO_HEADS: [&str; 7] = ["g", "gy", "gyr", "gyro", "omega", "w", "wrss"];
/// Words inside a longer name that say it is the accelerometer's.
const ACCEL_WORDS: [&str; 1] = ["acc"];
/// Words inside a longer name that say it is the gyro's.
const GYRO_WORDS: [&str; 3] = ["gyr", "rot", "omega"];
/// Unit words after the axis letter that say nothing about which quantity it is.
const UNIT_TAILS: [&str; 7] = ["g", "mg", "dps", "ms2", "rads", "raw", "ns"];

/// The columns of a stream with `count` values a line, named by `names` (header or labels; may be empty).
pub(super) fn name_columns(
    dialect: Dialect,
    names: &[String],
    count: usize,
    data: &[&Fields],
) -> Result<Columns, StreamError> {
    if !names.is_empty() {
        if let Some(columns) = by_names(names) {
            return Ok(columns);
        }
    }
    match (dialect, count) {
        (Dialect::Motioncal, 9) | (_, 3) | (_, 6) => Ok(by_order(None, 0, count >= 6)),
        (_, 4) | (_, 7) if grows(data) => Ok(by_order(Some((0, "first column".into())), 1, count == 7)),
        // NOTE: seven values and no clock are the registers from ACCEL_XOUT_H on, in their order
        // (register map 4.17-4.19): accelerometer, temperature, gyro.
        (_, 7) => Ok(Columns { time: None, accel: [0, 1, 2], gyro: Some([4, 5, 6]) }),
        _ => Err(StreamError::UnclearColumns { count, names: names.join(",") }),
    }
}

fn by_order(time: Option<(usize, String)>, first: usize, gyro: bool) -> Columns {
    let axes = |start: usize| [start, start + 1, start + 2];
    Columns { time, accel: axes(first), gyro: gyro.then(|| axes(first + 3)) }
}

fn by_names(names: &[String]) -> Option<Columns> {
    let keys: Vec<String> = names.iter().map(|n| key(n)).collect();
    let time = keys.iter().position(|k| TIME_NAMES.contains(&k.as_str()) || k.starts_with("timestamp"));
    let accel = axes(&keys, &ACCEL_HEADS)?;
    Some(Columns { time: time.map(|i| (i, names[i].clone())), accel, gyro: axes(&keys, &GYRO_HEADS) })
}

/// A column name reduced to lower-case letters and digits, its unit in brackets dropped.
fn key(name: &str) -> String {
    let name = name.split(['[', '(']).next().unwrap_or(name);
    name.chars().filter(|c| c.is_ascii_alphanumeric()).collect::<String>().to_ascii_lowercase()
}

/// The x, y, z columns whose names are one of `heads` and the axis letter, else those whose names
/// hold the quantity's word (`wordy`) before or after the axis letter (ESPHome's `MPU6050 Accel X`,
/// kriswiner's `X-acceleration`, ESP-IDF's `acce_x`); an angle (`ACC ANGLE X`) is no reading.
fn axes(keys: &[String], heads: &[&str]) -> Option<[usize; 3]> {
    let exact =
        |axis: char| keys.iter().position(|k| axis_of(k).is_some_and(|(head, a)| a == axis && heads.contains(&head)));
    let gyro = heads.contains(&"gyro");
    let wordy = |axis: char| keys.iter().position(|k| wordy_axis(k, gyro) == Some(axis));
    let find = |axis: char| exact(axis).or_else(|| wordy(axis));
    Some([find('x')?, find('y')?, find('z')?])
}

/// The axis of a key that names the gyro (`gyro`) or the accelerometer in a longer word, the axis
/// letter last or first.
fn wordy_axis(key: &str, gyro: bool) -> Option<char> {
    let words: &[&str] = if gyro { &GYRO_WORDS } else { &ACCEL_WORDS };
    let names = |head: &str| words.iter().any(|w| head.contains(w)) && !head.contains("angle");
    let last = key.chars().last().filter(|c| matches!(c, 'x' | 'y' | 'z') && names(&key[..key.len() - 1]));
    last.or_else(|| key.chars().next().filter(|c| matches!(c, 'x' | 'y' | 'z') && names(&key[1..])))
}

/// A key split into its head and axis letter: `accelx` -> (`accel`, x), `axg` -> (`a`, x).
fn axis_of(key: &str) -> Option<(&str, char)> {
    let stem = UNIT_TAILS
        .iter()
        .filter_map(|tail| key.strip_suffix(tail))
        .find(|stem| stem.ends_with(['x', 'y', 'z']))
        .unwrap_or(key);
    let axis = stem.chars().last().filter(|c| matches!(c, 'x' | 'y' | 'z'))?;
    Some((&stem[..stem.len() - 1], axis))
}

/// Whether the first value grows from line to line on every line looked at: a clock.
fn grows(data: &[&Fields]) -> bool {
    data.len() >= 3 && data.windows(2).all(|pair| pair[1].values[0] > pair[0].values[0])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(text: &str) -> Vec<String> {
        text.split(',').map(str::to_owned).collect()
    }

    #[test]
    fn columns_are_found_by_the_names_sketches_and_kalibr_give_them() {
        let csv = by_names(&names("millis,ax,ay,az,gx,gy,gz")).unwrap();
        assert_eq!((csv.time.map(|t| t.0), csv.accel, csv.gyro), (Some(0), [1, 2, 3], Some([4, 5, 6])));
        let kalibr = by_names(&names("timestamp,omega_x,omega_y,omega_z,alpha_x,alpha_y,alpha_z")).unwrap();
        assert_eq!((kalibr.accel, kalibr.gyro), ([4, 5, 6], Some([1, 2, 3])));
        let euroc = by_names(&names("#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]"));
        assert_eq!(euroc.map(|c| c.accel), Some([4, 5, 6]));
        let plot = by_names(&names("AccelX,AccelY,AccelZ,GyroX,GyroY,GyroZ")).unwrap();
        assert_eq!((plot.time, plot.accel, plot.gyro), (None, [0, 1, 2], Some([3, 4, 5])));
        assert_eq!(by_names(&names("AcX,AcY,AcZ,Tmp,GyX,GyY,GyZ")).map(|c| c.gyro), Some(Some([4, 5, 6])));
        assert_eq!(by_names(&names("ax_g,ay_g,az_g")).map(|c| (c.accel, c.gyro)), Some(([0, 1, 2], None)));
        assert!(by_names(&names("temp,pressure,humidity")).is_none());
    }
}
