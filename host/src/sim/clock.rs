//! How simulated time runs: fast-forward (tests, `--sim`, `sim --pty --fast`) or real time
//! (`sim --pty`, so a person sees progress, can press Ctrl-C and can move the board mid-capture).

use std::time::{Duration, Instant};

/// Simulated time per service loop when fast-forwarding, in microseconds.
const FAST_TICK_US: u64 = 10_000;
/// Largest step of simulated time in real time, in microseconds: a loop held up longer (a slow
/// machine, a debugger) is not made up for in one jump that would overflow the sensor FIFO.
const MAX_REAL_STEP_US: u64 = 100_000;

/// The pace of simulated time.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Pace {
    /// 10 ms of simulated time per service loop: as fast as the loop runs while the board works,
    /// about real speed while it is idle.
    Fast,
    /// As `Fast` while the board works, each step only once the host has acted on everything sent
    /// to it (over an in-memory pipe); while it is idle, time stands still, so the samples a run
    /// sees depend on its seed and its requests alone, never on how fast the host happens to be.
    Lockstep,
    /// Simulated time follows the wall clock.
    RealTime,
}

/// Simulated time, handed out step by step.
pub(super) struct Clock {
    pace: Pace,
    last: Instant,
}

impl Clock {
    /// A clock running at `pace` from now.
    pub(super) fn new(pace: Pace) -> Self {
        Clock { pace, last: Instant::now() }
    }

    /// Microseconds of simulated time to let pass now, the board `busy` or not.
    pub(super) fn step_us(&mut self, busy: bool) -> u64 {
        self.step_us_at(busy, Instant::now())
    }

    /// The step of [`Clock::step_us`] taken at the instant `now`.
    fn step_us_at(&mut self, busy: bool, now: Instant) -> u64 {
        match self.pace {
            Pace::Fast => FAST_TICK_US,
            Pace::Lockstep if busy => FAST_TICK_US,
            Pace::Lockstep => 0,
            Pace::RealTime => {
                let elapsed = now.duration_since(self.last).as_micros();
                self.last = now;
                mutant!(
                    "sim-clock-one-jump",
                    u64::try_from(elapsed).unwrap_or(u64::MAX).min(MAX_REAL_STEP_US),
                    u64::try_from(elapsed).unwrap_or(u64::MAX)
                )
            }
        }
    }

    /// Simulated time stands still (the board waits for the host to read what it wrote).
    pub(super) fn hold(&mut self) {
        self.last = Instant::now();
    }

    /// Whether time steps only once the host has caught up.
    pub(super) fn in_lockstep(&self) -> bool {
        self.pace == Pace::Lockstep
    }

    /// How long a read waits for the host: no wait while the board works and time is fast-forwarded.
    pub(super) fn read_wait(&self, busy: bool) -> Duration {
        match (self.pace, busy) {
            (Pace::Fast | Pace::Lockstep, true) => Duration::ZERO,
            _ => Duration::from_micros(FAST_TICK_US),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn real_time_follows_the_wall_clock_and_stands_still_while_held() {
        // Instants are given, not slept for: the test asserts no duration of the machine's own.
        let mut clock = Clock::new(Pace::RealTime);
        let start = clock.last;
        assert_eq!(clock.step_us_at(false, start + Duration::from_millis(30)), 30_000);
        let stalled = start + Duration::from_millis(530);
        assert_eq!(clock.step_us_at(true, stalled), MAX_REAL_STEP_US, "a stall is not made up in one jump");
        let before_hold = Instant::now();
        clock.hold();
        assert!(clock.last >= before_hold, "time held still must not be made up");
        assert_eq!(clock.step_us_at(true, clock.last + Duration::from_millis(2)), 2_000);
        assert_eq!(Clock::new(Pace::Fast).step_us(false), FAST_TICK_US);
    }

    #[test]
    fn lockstep_time_passes_only_while_the_board_works() {
        let mut clock = Clock::new(Pace::Lockstep);
        let later = clock.last + Duration::from_millis(20);
        assert_eq!(clock.step_us_at(false, later), 0);
        assert_eq!(clock.step_us_at(true, later), FAST_TICK_US);
    }
}
