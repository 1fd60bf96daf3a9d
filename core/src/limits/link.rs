//! The thresholds of the link to a board and of the lot database: how long a port is listened to,
//! how much silence means a board is gone, the baud rates allowed, and a writer's wait.

use std::time::Duration;

/// How long a port is listened to before anything is written to it: a sketch printing at 1 Hz or
/// faster has said something by then.
pub const LISTEN_FIRST: Duration = Duration::from_millis(1200);

/// Longest silence from a device before it is declared gone.
///
/// NOTE: a pulled cable or a reset board is named within two seconds instead of waited on; the
/// firmware's replies come well within it.
pub const SILENCE_LIMIT: Duration = Duration::from_secs(2);

/// The baud rates a port may be opened at: from the slowest rate a sketch prints a sensor at to
/// the fastest USB UART bridges (CP2102 and FT232R 3 MBd, CH343 6 MBd).
pub const BAUD_RANGE: std::ops::RangeInclusive<u32> = 300..=6_000_000;

/// How long a lot writer waits for another writer's transaction to end before it gives up.
///
/// NOTE: a writer holds the database for one certificate's insert, milliseconds; half a minute
/// covers a machine stalled for a while, and a writer holding it longer is stuck.
pub const LOT_BUSY_WAIT: Duration = Duration::from_secs(30);

/// How many standard errors a station's mean of a parameter may lie from the other stations' before
/// the lot names it drifting (`lot show --by station`).
///
/// NOTE: 12 parameters on 8 stations are 96 comparisons; 4 standard errors of a normal mean are
/// passed by chance with 6.3e-5 each, about 1 in 160 lots with no drift at all.
pub const STATION_DRIFT_STANDARD_ERRORS: f64 = 4.0;
/// The fewest boards a station (and the others together) need before its mean is judged.
pub const STATION_DRIFT_MIN_BOARDS: usize = 5;
