//! Several boards on one fixture, turned by one hand, each board's session in its own thread: the
//! core's `run::fixture`, and where the threads meet. What a meeting decides (who is waited for, the
//! answer, one time for the boards whose time the fixture keeps, who leads) is the core's
//! [`Meeting`]; here it is held under a lock, each board's thread blocked until its meeting is held,
//! and the boards whose time the fixture keeps ([`TimedMember`]) are read and told. Each board's
//! hand is the core's [`FixtureHand`], meeting the others at its [`Seat`].

use std::sync::{Arc, Condvar, Mutex, MutexGuard};

pub use accelcal_core::run::fixture::{Arrival, FixtureHand, Meeting, MeetingPlace, Ticket, Wait};

use super::Hand;

/// A board whose time the fixture keeps: one whose time passes only when it is told (a simulated
/// board, `sim::SimulatedMember`); a real board keeps its own time and is no such member.
pub trait TimedMember: Send + Sync {
    /// The board's own time, in seconds.
    fn now_s(&self) -> f64;
    /// Lets `seconds` pass on the board: the time it waited for the others on the fixture.
    fn wait(&self, seconds: f64);
    /// The board has just been turned for the `turns`-th time (from 1).
    fn turned(&self, turns: usize);
}

/// The boards on one fixture and where their threads meet.
pub struct Fixture {
    meeting: Mutex<Meeting>,
    met: Condvar,
    timed: Vec<Option<Box<dyn TimedMember>>>,
}

impl Fixture {
    /// A fixture of these boards (`None` for a real board, which keeps its own time).
    pub fn new(timed: Vec<Option<Box<dyn TimedMember>>>) -> Arc<Self> {
        Arc::new(Fixture { meeting: Mutex::new(Meeting::new(timed.len())), met: Condvar::new(), timed })
    }

    /// A board alone.
    pub fn alone() -> Arc<Self> {
        Fixture::new(vec![None])
    }

    /// The seat of board `index`; the board leaves the fixture when its seat is dropped.
    pub fn seat(self: &Arc<Self>, index: usize) -> Seat {
        Seat { fixture: self.clone(), index }
    }

    fn lock(&self) -> MutexGuard<'_, Meeting> {
        // NOTE: a thread that panicked while holding the lock left the meeting as it was.
        self.meeting.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
    }

    /// Board `index` arrives saying whether it has `enough`; returns once every board still on the
    /// fixture has arrived, with whether all had enough.
    fn meet(&self, index: usize, enough: bool) -> bool {
        let mut meeting = self.lock();
        let ticket = match meeting.arrive(index, enough) {
            Arrival::Alone(answer) => return answer,
            Arrival::Waits(ticket) => ticket,
            Arrival::Holds(ticket) => {
                self.hold(&mut meeting);
                ticket
            }
        };
        loop {
            if let Some(answer) = meeting.answer_to(ticket) {
                return answer;
            }
            meeting = self.met.wait(meeting).unwrap_or_else(|poisoned| poisoned.into_inner());
        }
    }

    /// Board `index` leaves; the others no longer wait for it.
    fn leave(&self, index: usize) {
        let mut meeting = self.lock();
        if meeting.leave(index) {
            self.hold(&mut meeting);
        }
    }

    /// Everyone is here: the meeting held with the timed boards' clocks, each told its wait, and
    /// the boards that waited let go.
    fn hold(&self, meeting: &mut Meeting) {
        let now_s = self.clocks(meeting);
        for wait in meeting.hold(&now_s) {
            if let Some(Some(member)) = self.timed.get(wait.board) {
                member.wait(wait.seconds);
            }
        }
        self.met.notify_all();
    }

    /// Each board's own time, in seconds, for the timed boards still on the fixture (the clocks of
    /// the others are not read).
    fn clocks(&self, meeting: &Meeting) -> Vec<Option<f64>> {
        let clock = |(index, member): (usize, &Option<Box<dyn TimedMember>>)| {
            member.as_ref().filter(|_| meeting.is_on(index)).map(|member| member.now_s())
        };
        self.timed.iter().enumerate().map(clock).collect()
    }
}

/// A board's place on a fixture.
pub struct Seat {
    fixture: Arc<Fixture>,
    index: usize,
}

impl Seat {
    /// The board's hand as the fixture's: `own` turns this board (or speaks to the person holding
    /// the fixture, `speaks_for_all`, said once for all boards).
    pub fn hand(&self, own: Box<dyn Hand>, speaks_for_all: bool) -> FixtureHand {
        // NOTE: the hand does not hold the seat: a board stays on the fixture between its hands (the
        // collection's, the verification's) and leaves only when its session ends.
        let place = Place { fixture: self.fixture.clone(), index: self.index };
        FixtureHand::new(Box::new(place), own, speaks_for_all)
    }

    /// Which board of the fixture this is (0-based).
    pub fn index(&self) -> usize {
        self.index
    }
}

impl Drop for Seat {
    fn drop(&mut self) {
        self.fixture.leave(self.index);
    }
}

/// Where board `index`'s hand meets the others: blocks its thread until the meeting is held.
struct Place {
    fixture: Arc<Fixture>,
    index: usize,
}

impl MeetingPlace for Place {
    fn meet(&mut self, enough: bool) -> bool {
        self.fixture.meet(self.index, enough)
    }

    fn leads(&self) -> bool {
        self.fixture.lock().leads(self.index)
    }

    fn turned(&mut self, turns: usize) {
        if let Some(Some(member)) = self.fixture.timed.get(self.index) {
            member.turned(turns);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::procedure::{Orientation, PersonHand, Silent};

    #[test]
    fn the_threads_meet_go_on_while_any_needs_a_position_and_wait_for_none_that_left() {
        let fixture = Fixture::new(vec![None, None, None]);
        let mut seats: Vec<Option<Seat>> = (0..3).map(|index| Some(fixture.seat(index))).collect();
        let answers = std::thread::scope(|scope| {
            let first = scope.spawn(|| fixture.meet(0, true));
            let second = scope.spawn(|| fixture.meet(1, false));
            let third = fixture.meet(2, true);
            (first.join().unwrap(), second.join().unwrap(), third)
        });
        assert_eq!(answers, (false, false, false), "one board short of positions keeps the hand going for all");
        seats[1] = None;
        let answers = std::thread::scope(|scope| {
            let first = scope.spawn(|| fixture.meet(0, true));
            let third = fixture.meet(2, true);
            (first.join().unwrap(), third)
        });
        assert_eq!(answers, (true, true), "the board that left is not waited for");
        // A board waiting alone is let go when the last other board leaves.
        std::thread::scope(|scope| {
            let waiting = scope.spawn(|| fixture.meet(0, false));
            while fixture.lock().arrived() == 0 {
                std::thread::yield_now();
            }
            seats[2] = None;
            assert!(!waiting.join().unwrap());
        });
        let leads = |index| fixture.lock().leads(index);
        assert!(leads(0) && !leads(2));
    }

    /// A board whose clock stands still, as when its thread has not yet taken the waits it was
    /// told; it records them, and its turns.
    struct StandingClock {
        now_s: f64,
        told: Arc<Mutex<Vec<String>>>,
    }

    impl TimedMember for StandingClock {
        fn now_s(&self) -> f64 {
            self.now_s
        }
        fn wait(&self, seconds: f64) {
            self.told.lock().unwrap().push(format!("wait {seconds}"));
        }
        fn turned(&self, turns: usize) {
            self.told.lock().unwrap().push(format!("turned {turns}"));
        }
    }

    #[test]
    fn timed_boards_turned_on_their_threads_are_told_one_wait_and_each_turn() {
        let member = |now_s: f64| {
            let told = Arc::new(Mutex::new(Vec::new()));
            (Box::new(StandingClock { now_s, told: told.clone() }) as Box<dyn TimedMember>, told)
        };
        let ((ahead, ahead_told), (behind, behind_told)) = (member(10.0), member(4.0));
        let fixture = Fixture::new(vec![Some(ahead), Some(behind)]);
        let seats = [fixture.seat(0), fixture.seat(1)];
        let target = Orientation::named("+X").unwrap();
        let turn_three_times = |seat: &Seat| {
            let mut hand = seat.hand(Box::new(PersonHand), true);
            (0..3).for_each(|_| hand.present(&target, &mut Silent { yes: true }).unwrap());
        };
        std::thread::scope(|scope| seats.iter().for_each(|seat| drop(scope.spawn(|| turn_three_times(seat)))));
        let told = |told: &Arc<Mutex<Vec<String>>>| told.lock().unwrap().clone();
        let turns = ["turned 1", "turned 2", "turned 3"];
        assert_eq!(told(&ahead_told), turns, "the latest board waits for none");
        assert_eq!(told(&behind_told)[0], "wait 6", "one wait of the 6 s between the boards, however often they meet");
        assert_eq!(told(&behind_told)[1..], turns);
    }
}
