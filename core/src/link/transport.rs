//! What the link needs of the host: bytes written and read, the time, and whether the person asked
//! to stop. A serial port, the browser's Web Serial and a simulated board in memory each are one.

use std::time::Duration;

use super::LinkError;

/// The bytes to and from one board as the host moves them, and the host's clock.
// NOTE: async, so that a host whose port answers later (the browser) drives the same link as one that
// blocks (the command line, whose futures are ready at once); the core never waits by itself.
#[allow(async_fn_in_trait)]
pub trait Transport {
    /// Writes `bytes` whole.
    async fn write(&mut self, bytes: &[u8]) -> Result<(), LinkError>;
    /// What arrived into `buffer`, waiting a short while at most: the count, 0 when nothing came; an
    /// error when the board is gone.
    async fn read(&mut self, buffer: &mut [u8]) -> Result<usize, LinkError>;
    /// The host's time since an origin of its own.
    fn now(&self) -> Duration;
    /// The date now, in seconds since the Unix epoch, for the records a run keeps.
    fn unix_time_s(&self) -> f64;
    /// Whether the person asked to stop (Ctrl-C): the running request is cancelled on the board.
    fn interrupted(&self) -> bool {
        false
    }
}
