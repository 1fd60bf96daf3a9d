//! What the user sees and answers during the procedure.

/// What the user sees and answers.
pub trait Feedback {
    /// A line of instruction or result.
    fn say(&mut self, line: &str);
    /// The live state of the board (replaced by the next one).
    fn live(&mut self, line: &str);
    /// A capture's progress.
    fn progress(&mut self, samples: u32, total: u32);
    /// The capture ended.
    fn progress_done(&mut self);
    /// A yes/no question; `true` for yes.
    fn confirm(&mut self, question: &str) -> bool;
}

/// No output: for `--json` and tests. Questions get the answer `yes`.
pub struct Silent {
    /// The answer to every question.
    pub yes: bool,
}

impl Feedback for Silent {
    fn say(&mut self, _: &str) {}
    fn live(&mut self, _: &str) {}
    fn progress(&mut self, _: u32, _: u32) {}
    fn progress_done(&mut self) {}
    fn confirm(&mut self, _: &str) -> bool {
        self.yes
    }
}

/// Keeps what the person is told (tests, a host that shows it later); questions get the answer `yes`.
pub struct Told(pub Vec<String>);

impl Feedback for Told {
    fn say(&mut self, line: &str) {
        self.0.push(line.to_owned());
    }
    fn live(&mut self, _: &str) {}
    fn progress(&mut self, _: u32, _: u32) {}
    fn progress_done(&mut self) {}
    fn confirm(&mut self, _: &str) -> bool {
        true
    }
}
