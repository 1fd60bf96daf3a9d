//! Several boards in one fixture, turned by one hand: each board runs its own session (its own
//! stillness, captures, fit and verification) in its own thread, and the sessions meet wherever the
//! hand acts, so that the fixture is turned once for all of them. A board alone is a fixture of one.
//!
//! Where they meet: before every turn (each board's hand call), and at the adaptive session's
//! question whether to ask for another position (the hand goes on while any board needs one). A
//! board that stops (done, failed, pulled) leaves the fixture and the others go on without it.
//! Boards whose time passes only when they are told (simulated ones) keep one time: when they
//! meet, a board that finished its work early lets the time it waited pass ([`TimedMember::wait`]),
//! as a real board on the fixture would have waited.

use std::sync::{Arc, Condvar, Mutex, MutexGuard};

use super::{Feedback, Hand, Orientation, ProcedureError};

/// Shorter waits than this (seconds) are not passed on to a board whose time the fixture keeps.
const LEAST_WAIT_S: f64 = 1e-4;

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

/// The boards on one fixture and where they meet.
pub struct Fixture {
    state: Mutex<Meeting>,
    met: Condvar,
    timed: Vec<Option<Box<dyn TimedMember>>>,
}

/// Who is on the fixture, who has arrived at this meeting, and what they said.
struct Meeting {
    on_fixture: Vec<bool>,
    arrived: usize,
    all_enough: bool,
    /// Counts the meetings held; a waiter leaves once it moves on.
    held: u64,
    /// The last meeting's answer: whether every board had enough.
    answer: bool,
    /// The time, in seconds, each timed board was last told to wait until: its clock may not show
    /// it yet, as the board takes its commands in its own thread.
    waited_until_s: Vec<f64>,
}

impl Fixture {
    /// A fixture of these boards (`None` for a real board, which keeps its own time).
    pub fn new(timed: Vec<Option<Box<dyn TimedMember>>>) -> Arc<Self> {
        let boards = timed.len();
        let meeting = Meeting {
            on_fixture: vec![true; boards],
            arrived: 0,
            all_enough: true,
            held: 0,
            answer: true,
            waited_until_s: vec![f64::NEG_INFINITY; boards],
        };
        Arc::new(Fixture { state: Mutex::new(meeting), met: Condvar::new(), timed })
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
        // NOTE: a thread that panicked while holding the lock left the counts as they were.
        self.state.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
    }

    /// Board `index` arrives saying whether it has `enough`; returns once every board still on the
    /// fixture has arrived, with whether all had enough.
    fn meet(&self, index: usize, enough: bool) -> bool {
        let mut meeting = self.lock();
        if !meeting.on_fixture.get(index).copied().unwrap_or(false) {
            return enough;
        }
        meeting.arrived += 1;
        meeting.all_enough &= enough;
        let held = meeting.held;
        if meeting.arrived >= meeting.present() {
            self.hold(&mut meeting);
        }
        while meeting.held == held {
            meeting = self.met.wait(meeting).unwrap_or_else(|poisoned| poisoned.into_inner());
        }
        meeting.answer
    }

    /// Board `index` leaves; the others no longer wait for it.
    fn leave(&self, index: usize) {
        let mut meeting = self.lock();
        if let Some(on) = meeting.on_fixture.get_mut(index) {
            *on = false;
        }
        if meeting.arrived > 0 && meeting.arrived >= meeting.present() {
            self.hold(&mut meeting);
        }
    }

    /// Everyone is here: the answer, one time for the timed boards, and the next meeting.
    fn hold(&self, meeting: &mut Meeting) {
        meeting.answer = meeting.all_enough;
        (meeting.arrived, meeting.all_enough, meeting.held) = (0, true, meeting.held + 1);
        self.keep_one_time(meeting);
        self.met.notify_all();
    }

    /// Lets each timed board on the fixture wait until the latest one's time.
    fn keep_one_time(&self, meeting: &mut Meeting) {
        // NOTE: a board's time is the later of its clock and the time it was already told to wait
        // until: a Wait sent at the last meeting may not have reached its clock yet (the board runs
        // in its own thread), and telling it again would make it wait twice (seen under load: 71 s
        // on the fixture for 56 s alone).
        let members: Vec<(usize, &dyn TimedMember, f64)> = (self.timed.iter().enumerate())
            .filter(|(index, _)| meeting.on_fixture[*index])
            .filter_map(|(index, member)| member.as_deref().map(|m| (index, m)))
            .map(|(index, member)| (index, member, member.now_s().max(meeting.waited_until_s[index])))
            .collect();
        let latest_s = members.iter().map(|(_, _, now_s)| *now_s).fold(f64::NEG_INFINITY, f64::max);
        for (index, member, now_s) in members {
            let waited_s = latest_s - now_s;
            if waited_s > LEAST_WAIT_S {
                member.wait(waited_s);
                meeting.waited_until_s[index] = latest_s;
            }
        }
    }

    /// Whether board `index` is the first still on the fixture (the one whose instructions a
    /// person hears for all).
    fn leads(&self, index: usize) -> bool {
        self.lock().on_fixture.iter().position(|&on| on) == Some(index)
    }
}

impl Meeting {
    fn present(&self) -> usize {
        self.on_fixture.iter().filter(|&&on| on).count()
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
        FixtureHand { fixture: self.fixture.clone(), index: self.index, own, speaks_for_all, turns: 0 }
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

/// One board's hand on a fixture: every turn waits for the other boards, then turns this board.
pub struct FixtureHand {
    fixture: Arc<Fixture>,
    index: usize,
    own: Box<dyn Hand>,
    speaks_for_all: bool,
    turns: usize,
}

impl FixtureHand {
    /// Meets the other boards, then lets `act` turn this board (once for all when it speaks to a
    /// person), then tells a timed board it was turned.
    fn turn(
        &mut self,
        feedback: &mut dyn Feedback,
        act: impl FnOnce(&mut dyn Hand, &mut dyn Feedback) -> Result<(), ProcedureError>,
    ) -> Result<(), ProcedureError> {
        let (fixture, index) = (&self.fixture, self.index);
        fixture.meet(index, true);
        self.turns += 1;
        if !self.speaks_for_all || fixture.leads(index) {
            act(self.own.as_mut(), feedback)?;
        }
        if let Some(member) = &fixture.timed[index] {
            member.turned(self.turns);
        }
        Ok(())
    }
}

impl Hand for FixtureHand {
    fn present(&mut self, target: &Orientation, feedback: &mut dyn Feedback) -> Result<(), ProcedureError> {
        self.turn(feedback, |hand, feedback| hand.present(target, feedback))
    }

    fn fresh(&mut self, index: usize, feedback: &mut dyn Feedback) -> Result<(), ProcedureError> {
        self.turn(feedback, |hand, feedback| hand.fresh(index, feedback))
    }

    fn turn_quarter(&mut self, feedback: &mut dyn Feedback) -> Result<(), ProcedureError> {
        self.turn(feedback, |hand, feedback| hand.turn_quarter(feedback))
    }

    fn avoid(&mut self, orientations: &[[f64; 3]]) {
        self.own.avoid(orientations);
    }

    fn all_have_enough(&mut self, this_board: bool) -> bool {
        self.fixture.meet(self.index, this_board)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_boards_go_on_while_any_needs_a_position_and_wait_for_none_that_left() {
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
            while fixture.lock().arrived == 0 {
                std::thread::yield_now();
            }
            seats[2] = None;
            assert!(!waiting.join().unwrap());
        });
        assert!(fixture.leads(0) && !fixture.leads(2));
    }

    /// A board whose clock stands still, as when its thread has not yet taken the waits it was
    /// told; it records them.
    struct StandingClock {
        now_s: f64,
        waits_s: Arc<Mutex<Vec<f64>>>,
    }

    impl TimedMember for StandingClock {
        fn now_s(&self) -> f64 {
            self.now_s
        }
        fn wait(&self, seconds: f64) {
            self.waits_s.lock().unwrap().push(seconds);
        }
        fn turned(&self, _: usize) {}
    }

    #[test]
    fn a_board_told_to_wait_is_not_told_again_before_its_clock_shows_the_wait() {
        let member = |now_s: f64| {
            let waits_s = Arc::new(Mutex::new(Vec::new()));
            (Box::new(StandingClock { now_s, waits_s: waits_s.clone() }) as Box<dyn TimedMember>, waits_s)
        };
        let ((ahead, ahead_waits), (behind, behind_waits)) = (member(10.0), member(4.0));
        let fixture = Fixture::new(vec![Some(ahead), Some(behind)]);
        for _ in 0..3 {
            let mut meeting = fixture.lock();
            fixture.hold(&mut meeting);
        }
        assert_eq!(
            *behind_waits.lock().unwrap(),
            vec![6.0],
            "one wait of the 6 s between the boards, however often they meet"
        );
        assert!(ahead_waits.lock().unwrap().is_empty(), "the latest board waits for none");
    }
}
