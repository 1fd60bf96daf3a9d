//! What the owner of a simulated board can do to it: below the board, its serve loop, the hand
//! and the lines a person types, which all speak it.

use firmware::sim::physics::Motion;

/// What the owner of a simulated board can do to it.
#[derive(Debug, Clone, PartialEq)]
pub enum SimCommand {
    /// Rest the board with this body-frame direction pointing up.
    Place([f32; 3]),
    /// Start moving.
    Move(Motion),
    /// Move for this many seconds of simulated time, then rest where the motion left the board.
    MoveFor { motion: Motion, seconds: f32 },
    /// Turn from where the board rests to rest with this body-frame direction up, as a hand does
    /// (the gyro sees the turn).
    TurnTo([f32; 3]),
    /// Tip the board over an edge by this many degrees, as a hand does: about the horizontal line
    /// across the board's x axis (its y axis when x points up).
    Tip(f32),
    /// Move the surroundings towards a temperature (degC) at a rate (degC/s; infinite: at once).
    Ambient { target_c: f32, c_per_s: f32 },
    /// Let this many seconds pass at once while idle (a soak), without producing every sample.
    Elapse(f32),
    /// Let this many seconds pass while the board waits idle for others on its fixture: the
    /// temperature moves on, the noise stream does not (`SimMpu6050::wait_seconds`).
    Wait(f32),
    /// Disconnect or reconnect the sensor.
    Connect(bool),
    /// The link loses the next this many streamed samples (a flaky cable).
    LoseSamples(u32),
    /// Reboot the board (a reset or brown-out): RAM state is lost, the flash and the port stay.
    Restart,
    /// Stop serving and hand the flash back.
    Stop,
}
