//! Several boards on one fixture, turned by one hand: the rules of their meetings, free of I/O.
//! Each board runs its own session, and the sessions meet wherever the hand acts (before every turn,
//! and at the adaptive session's question whether to ask for another position), so that the
//! fixture is turned once for all of them; a board alone is a fixture of one. A board that stops
//! (done, failed, pulled) leaves the fixture and the others go on without it. Boards whose time passes only when they are told
//! (simulated ones) keep one time: when they meet, a board that finished its work early is told to
//! let the time it waited pass, as a real board on the fixture would have waited.
//!
//! [`Meeting`] decides; the host holds it under a lock and blocks each board until its meeting is
//! held (`procedure::Fixture`, one thread per board). The hand that meets before every turn is
//! [`FixtureHand`], over the host's [`MeetingPlace`].

mod hand;

pub use hand::{FixtureHand, MeetingPlace};

/// Shorter waits than this (seconds) are not passed on to a board whose time the fixture keeps.
const LEAST_WAIT_S: f64 = 1e-4;

/// The meetings of the boards on one fixture: who is on it, who has arrived at the meeting to come
/// and what they said, the last meeting's answer, and the time each board whose time the fixture
/// keeps was told to wait until.
#[derive(Debug, Clone)]
pub struct Meeting {
    on_fixture: Vec<bool>,
    arrived: usize,
    all_enough: bool,
    /// Counts the meetings held; a board that waits holds the number of the one it waits for.
    held: u64,
    /// The last meeting's answer: whether every board had enough.
    answer: bool,
    /// The time, in seconds, each board was last told to wait until: its clock may not show it
    /// yet, as the board takes its commands in its own time.
    waited_until_s: Vec<f64>,
}

/// The meeting a board that arrived waits for (the number of meetings held before it).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Ticket(u64);

/// What became of a board that arrived at a meeting.
#[must_use]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Arrival {
    /// The board is no longer on the fixture: it meets no one, and its own answer stands.
    Alone(bool),
    /// Others are still to come: it waits until its meeting is held ([`Meeting::answer_to`]).
    Waits(Ticket),
    /// It was the last to come: the meeting is to be held at once ([`Meeting::hold`]).
    Holds(Ticket),
}

/// A board whose time the fixture keeps, to be told to let `seconds` pass: the time it waited for
/// the latest board on the fixture.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wait {
    /// Which board of the fixture (0-based).
    pub board: usize,
    /// How long it lets pass, in seconds.
    pub seconds: f64,
}

impl Meeting {
    /// The meetings of `boards` boards, all on the fixture and none arrived.
    pub fn new(boards: usize) -> Self {
        Meeting {
            on_fixture: vec![true; boards],
            arrived: 0,
            all_enough: true,
            held: 0,
            answer: true,
            waited_until_s: vec![f64::NEG_INFINITY; boards],
        }
    }

    /// Board `board` arrives saying whether it has `enough`: it waits for the others, or, the last
    /// of those still on the fixture to come, has the meeting held at once.
    pub fn arrive(&mut self, board: usize, enough: bool) -> Arrival {
        if !self.is_on(board) {
            return Arrival::Alone(enough);
        }
        self.arrived += 1;
        self.all_enough &= enough;
        let ticket = Ticket(self.held);
        if self.all_here() {
            Arrival::Holds(ticket)
        } else {
            Arrival::Waits(ticket)
        }
    }

    /// Board `board` leaves the fixture, and the others no longer wait for it; returns whether the
    /// rest had all arrived, so that the meeting is to be held at once ([`Meeting::hold`]).
    #[must_use]
    pub fn leave(&mut self, board: usize) -> bool {
        if let Some(on) = self.on_fixture.get_mut(board) {
            *on = false;
        }
        self.all_here()
    }

    /// Holds the meeting everyone still on the fixture came to: its answer, whether every one of
    /// them had enough, and one time for those whose time the fixture keeps. `now_s` is each board's
    /// own time in seconds, for the boards whose time the fixture keeps (`None` for the others);
    /// returns the waits to tell them.
    pub fn hold(&mut self, now_s: &[Option<f64>]) -> Vec<Wait> {
        self.answer = self.all_enough;
        (self.arrived, self.all_enough, self.held) = (0, true, self.held + 1);
        self.keep_one_time(now_s)
    }

    /// The answer of the meeting `ticket` waits for, once it was held: whether every board had enough.
    pub fn answer_to(&self, ticket: Ticket) -> Option<bool> {
        // NOTE: the meeting after it cannot be held before the board that waits arrives at it, so the
        // last answer is its meeting's.
        (self.held > ticket.0).then_some(self.answer)
    }

    /// Whether board `board` is the first still on the fixture: the one whose instructions a person
    /// hears for all.
    pub fn leads(&self, board: usize) -> bool {
        self.on_fixture.iter().position(|&on| on) == Some(board)
    }

    /// Whether board `board` is still on the fixture.
    pub fn is_on(&self, board: usize) -> bool {
        self.on_fixture.get(board).copied().unwrap_or(false)
    }

    /// How many boards have arrived at the meeting to come.
    pub fn arrived(&self) -> usize {
        self.arrived
    }

    /// Whether someone came and everyone still on the fixture has.
    fn all_here(&self) -> bool {
        let present = self.on_fixture.iter().filter(|&&on| on).count();
        self.arrived > 0 && self.arrived >= present
    }

    /// The waits that let each board on the fixture whose time it keeps reach the latest one's time.
    fn keep_one_time(&mut self, now_s: &[Option<f64>]) -> Vec<Wait> {
        // NOTE: a board's time is the later of its clock and the time it was already told to wait
        // until: a wait told at the last meeting may not have reached its clock yet (the board takes
        // its commands in its own time), and telling it again would make it wait twice (seen under
        // load: 71 s on the fixture for 56 s alone).
        let members: Vec<(usize, f64)> = (now_s.iter().enumerate())
            .filter(|(board, _)| self.is_on(*board))
            .filter_map(|(board, now_s)| now_s.map(|now_s| (board, now_s.max(self.waited_until_s[board]))))
            .collect();
        let latest_s = members.iter().map(|(_, now_s)| *now_s).fold(f64::NEG_INFINITY, f64::max);
        let waits: Vec<Wait> = (members.into_iter())
            .map(|(board, now_s)| Wait { board, seconds: latest_s - now_s })
            .filter(|wait| wait.seconds > LEAST_WAIT_S)
            .collect();
        waits.iter().for_each(|wait| self.waited_until_s[wait.board] = latest_s);
        waits
    }
}

#[cfg(test)]
mod tests;
