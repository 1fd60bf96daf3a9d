//! The thresholds of a foreign stream (someone's own sketch): how it is read, when it has stopped,
//! which stretches rest, and which units and rates it is taken to have.

/// A stream silent this long has stopped, in seconds (long enough that a busy machine's pause is not
/// taken for it).
pub const STREAM_QUIET_S: f64 = 10.0;

/// A live stream whose bytes hold no line of numbers this long is named unreadable (the wrong baud
/// rate, most likely), in seconds; after [`STREAM_QUIET_S`] so the session ends.
///
/// NOTE: a sketch prints several lines a second and its boot banner within one; five seconds of bytes
/// without a number is no pause of a working stream, and still short enough to act on.
pub const STREAM_UNREADABLE_S: f64 = 5.0;

/// Share of a file's characters that may be bytes that are not text (or control characters) for it to
/// be read as a log.
///
/// NOTE: an ESP32's boot noise is a handful of bytes in a log of megabytes; a program, a `.npy`
/// recording or a stream read at the wrong baud rate is more than half such bytes.
pub const NOT_TEXT_SHARE: f64 = 0.25;

/// Lines heard before the dialect of a live stream is decided.
///
/// NOTE: the dialect is the commonest shape of the lines; forty outnumber a board's boot banner of a
/// few lines many times over, and take a sketch printing at 10 Hz four seconds.
pub const LIVE_DETECTION_LINES: usize = 40;

/// Lines heard, none of them read as samples, before a live stream is refused with why.
///
/// NOTE: five times [`LIVE_DETECTION_LINES`]: a sample over eight lines (ESPHome's) shows its cycle
/// three times over well within them; a sketch at 10 Hz takes 20 s, one every 500 ms over four
/// lines 25 s, where before it was read nothing was said for minutes.
pub const LIVE_REFUSAL_LINES: usize = 200;

/// Seconds with no new still period, once every face and corner is rested, before a live session
/// short of fresh orientations ends with what it has.
///
/// NOTE: a turn and a hold of 7.5-9.5 s take a person well under 30 s; twice that with nothing new
/// is a board that cannot be turned further (mounted, or on a short cable), where before the
/// session waited for ever.
pub const FRESH_WAIT_S: f64 = 60.0;

/// Lines of a file looked at to find the dialect.
///
/// NOTE: a file's dialect is set by its first lines; 2000 lets the commonest shape stand out
/// whatever the banner, and reading them is instant.
pub const DETECTION_LINES: usize = 2000;

/// Most lines one sample is printed over (ESPHome's log: a `Got accel=...` line and one line for
/// each of its seven sensors).
pub const MAX_RECORD_LINES: usize = 8;

/// Share of the data lines that have the commonest shape for a stream to be one sample a line;
/// fewer, and the lines are looked at as a cycle of shapes (a sample over several lines).
///
/// NOTE: a boot banner or a `Cal1:` record every 50 lines leaves well over 90 % of the lines in one
/// shape; Adafruit's `basic_readings` (three lines a sample) leaves a third in each.
pub const ONE_LINE_SHARE: f64 = 0.6;

/// Cycles of shapes seen, at least, before lines are taken as one sample printed over several.
///
/// NOTE: three cycles of the same shapes in order do not happen by chance in a boot log.
pub const RECORD_REPEATS: usize = 3;

/// Shortest still period that counts as a position, in seconds.
///
/// NOTE: a person holds a position for several seconds; a hand pausing mid-turn holds under one.
pub const MIN_STILL_SEGMENT_S: f64 = 1.5;

/// A window's scatter may be this many times the median window's and still rest.
pub const STILL_SCATTER_FACTOR: f64 = 3.0;

/// Scatter that always counts as rest, in g: below a quantisation step of a printed value.
pub const STILL_SCATTER_FLOOR_G: f64 = 0.002;

/// A gyro within this many deg/s of its median rests: a hand's turn runs at 50-300 deg/s, and its
/// last 0.05 s, where the rate falls below this, turns the board by a few hundredths of a degree.
pub const STREAM_GYRO_STILL_DPS: f64 = 3.0;

/// A still period this close to a target, in degrees, has visited it.
///
/// NOTE: five degrees beyond the face tolerance, for a hand's rough placement; the edges lie 45
/// degrees from their faces, so no still period visits an edge and a face at once.
pub const VISITED_DEG: f64 = 25.0;

/// Fewest training periods for fresh ones to be held out: the live session's stop rule asks for
/// twelve, and `ortho9` needs nine.
pub const MIN_TRAINING_PERIODS: usize = 12;

/// How far the median |a| may be from 1 g in a unit for the stream to be taken as in that unit: the
/// units' sizes differ by 2x at least, a sensor's scale and offset errors by a few percent.
pub const UNIT_TOLERANCE: f64 = 0.25;

/// Noise more than this many times what the rate's band holds is folded in from above.
///
/// NOTE: the band is estimated from one period's scatter; half again is a margin over that
/// estimate's own error, so only noise clearly beyond the band is named as folded.
pub const FOLDED_NOISE_FACTOR: f64 = 1.5;

/// Fewest samples worth reading as a calibration stream.
///
/// NOTE: fewer hold no still period of [`MIN_STILL_SEGMENT_S`] at 20 Hz, nothing to calibrate from.
pub const STREAM_MIN_SAMPLES: usize = 30;

/// The widest accelerometer range of the sensors a sketch prints, in g.
///
/// NOTE: MPU-6050 Product Specification 6.2 (AFS_SEL = 3, +-16 g); the MPU-6500, MPU-9250 and
/// ICM-20948 stop at 16 g too. A value beyond it (with [`READABLE_MARGIN`]) is no reading.
pub const WIDEST_RANGE_G: f64 = 16.0;

/// The widest gyro range of the sensors a sketch prints, in deg/s.
///
/// NOTE: Product Specification 6.1 (FS_SEL = 3, +-2000 deg/s), the same on the parts above.
pub const WIDEST_RANGE_DPS: f64 = 2000.0;

/// The largest size of a value printed in counts: the output registers are 16-bit two's
/// complement (register map 4.17 and 4.19, ACCEL_XOUT_H ... GYRO_ZOUT_L), -32768 to 32767.
pub const COUNTS_SPAN: f64 = 32768.0;

/// How far beyond the sensor's reach a printed value may go and still be a sample: a sketch may
/// print counts less an offset or scaled by its own calibration, which moves them by a few percent;
/// a quarter more is no such correction.
pub const READABLE_MARGIN: f64 = 1.25;

/// Rates a sketch prints at, in Hz: a time unit that puts the rate outside is the wrong one.
pub const PLAUSIBLE_HZ: (f64, f64) = (0.5, 10_000.0);

/// Slowest stream whose turns are integrated: a hand's turn of 0.6-2 s at up to 300 deg/s is
/// followed by 25 or more samples at 40 Hz, each turning the board by at most 8 degrees.
pub const MIN_TURN_RATE_HZ: f64 = 40.0;

/// A G scale this close to a range's ratio names that range.
///
/// NOTE: the ranges' ratios are 2x apart; 10 % is far inside that and above a gyro's own scale
/// error (+-3 %, Product Specification 6.1).
pub const GYRO_RANGE_TOLERANCE: f64 = 0.1;

/// Largest gyro mean a resting board can read, in deg/s: more, and the gyro's values are not in the
/// unit they are read in (counts read as deg/s rest at hundreds).
///
/// NOTE: the MPU-6050's zero-rate output is within +-20 deg/s at 25 degC (Product Specification 6.1,
/// "Initial ZRO Tolerance"; +-5 on the MPU-6500 and ICM-20948); 2.5 times that is no chip's bias.
pub const GYRO_REST_MAX_DPS: f64 = 50.0;

/// Largest median distance of a resting board's gyro from its bias, in deg/s: more, and its values
/// are not in the unit they are read in.
///
/// NOTE: the MPU-6050's total noise is 0.05 deg/s rms at 100 Hz bandwidth (Product Specification
/// 6.1), about 0.1 with the low-pass open, and a board held still in a hand shakes by a few deg/s at
/// most; counts of +-250 deg/s read as deg/s scatter by 10-20 (131 counts a deg/s).
pub const GYRO_REST_SCATTER_MAX_DPS: f64 = 10.0;

/// Turns whose gravity moves this far, in degrees, say how far the gyro's values turn the board.
pub const UNIT_TURN_MIN_DEG: f64 = 45.0;

/// The gyro integrated over the turns may turn the board this many times as far as (or this many
/// times less than) gravity's direction moved and be in the unit it is read in.
///
/// NOTE: a hand's turn from face to face adds a twist about the vertical that gravity does not see,
/// up to about as much again (1.4x); the units the gyro may be in differ by 2x (ranges) to 131x
/// (counts as deg/s), and the range a factor 2 leaves open the turns' G fit names (`GYRO_RANGE_TOLERANCE`).
pub const UNIT_TURN_RATIO: f64 = 2.0;

/// Longest run of garbled timestamps passed over when the clock comes back in step after it, in lines.
///
/// NOTE: a garbled timestamp is a line corrupted on its way (a UART's noise burst, two tasks of a
/// sketch printing at once): a line or a few. A clock that leaves its sequence for longer and comes
/// back exactly in step is no clock that jumped; one that jumps and stays is a gap, counted.
pub const MAX_GLITCH_RUN: usize = 8;
