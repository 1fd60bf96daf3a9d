//! A person at a terminal: the run's feedback drawn as progress bars and a live line, questions
//! read from stdin, Ctrl-C turned into a flag the run heeds, and spinners for work of unknown length.

use std::io::{BufRead, IsTerminal, Write};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::RecvTimeoutError;
use std::sync::{Arc, OnceLock};
use std::time::{Duration, Instant};

use indicatif::{MultiProgress, ProgressBar, ProgressStyle};

use crate::procedure::{Feedback, Silent};

/// Progress bars and questions on stderr / stdin.
pub struct Terminal {
    /// Answer yes to every question without asking.
    pub assume_yes: bool,
    bar: Option<ProgressBar>,
    live: ProgressBar,
    /// The live line and the capture's bar drawn as one block.
    // NOTE: drawn apart, each redraw of one left a stale copy of the other in the scrollback.
    lines: MultiProgress,
    /// Where stderr is no terminal (a log, a pipe), the live line is drawn nowhere: it is written
    /// as a line of its own, at this pace.
    plain_live: Option<Pacing>,
}

/// How often a line that a terminal would redraw in place is written where nothing is redrawn:
/// every [`PLAIN_LIVE_EVERY`] from the first such line after an instruction, so that a log of a
/// long wait says what is awaited, and a short one adds no line.
pub struct Pacing {
    every: Duration,
    since: Option<Instant>,
}

/// A wait seen in a log says what it waits for at least this often.
pub const PLAIN_LIVE_EVERY: Duration = Duration::from_secs(10);

impl Pacing {
    pub fn new(every: Duration) -> Self {
        Pacing { every, since: None }
    }

    /// Whether a line is due at `now`; if so, it counts as written.
    pub fn due(&mut self, now: Instant) -> bool {
        let since = *self.since.get_or_insert(now);
        let due = now.saturating_duration_since(since) >= self.every;
        if due {
            self.since = Some(now);
        }
        due
    }

    /// A new instruction was given: its wait is counted from its first line.
    pub fn restart(&mut self) {
        self.since = None;
    }
}

impl Terminal {
    /// Feedback on the terminal; `assume_yes` for `--yes`.
    pub fn new(assume_yes: bool) -> Self {
        let lines = MultiProgress::new();
        let live = lines.add(ProgressBar::new_spinner());
        live.set_style(
            ProgressStyle::with_template("{spinner} {msg}").unwrap_or_else(|_| ProgressStyle::default_spinner()),
        );
        let plain_live = (!std::io::stderr().is_terminal()).then(|| Pacing::new(PLAIN_LIVE_EVERY));
        Terminal { assume_yes, bar: None, live, lines, plain_live }
    }

    fn ask(&mut self, question: &str) -> bool {
        self.lines.suspend(|| {
            eprint!("{question} [y/N] ");
            let _ = std::io::stderr().flush();
            answer_unless_ctrl_c().is_some_and(|answer| matches!(answer.trim(), "y" | "Y" | "yes"))
        })
    }
}

/// A flag that Ctrl-C sets (instead of ending the process), so that the capture is cancelled on
/// the board and the session stays as written; one for the process, its handler set once.
pub fn interrupt_on_ctrl_c() -> Arc<AtomicBool> {
    CTRL_C
        .get_or_init(|| {
            let flag = Arc::new(AtomicBool::new(false));
            let set = flag.clone();
            // NOTE: fails only when a handler is already set; without one, Ctrl-C ends the process
            // and the session still holds every capture written so far.
            let _ = ctrlc::set_handler(move || set.store(true, Ordering::SeqCst));
            flag
        })
        .clone()
}

static CTRL_C: OnceLock<Arc<AtomicBool>> = OnceLock::new();

/// The line the person types; `None` at once on Ctrl-C where the run handles it (a read of stdin
/// would hold Ctrl-C until Enter), or when stdin ends.
fn answer_unless_ctrl_c() -> Option<String> {
    let read_line = || {
        let mut answer = String::new();
        std::io::stdin().lock().read_line(&mut answer).ok().filter(|&n| n > 0).map(|_| answer)
    };
    let Some(ctrl_c) = CTRL_C.get() else { return read_line() };
    let (send, answer) = std::sync::mpsc::channel();
    // NOTE: the reader is left blocked on stdin when Ctrl-C comes first; the run ends soon after.
    std::thread::spawn(move || send.send(read_line()));
    loop {
        if ctrl_c.load(Ordering::SeqCst) {
            return None;
        }
        match answer.recv_timeout(CTRL_C_POLL) {
            Ok(line) => return line,
            Err(RecvTimeoutError::Timeout) => {}
            Err(RecvTimeoutError::Disconnected) => return None,
        }
    }
}

/// How often a question looks at the Ctrl-C flag while the person has not answered.
const CTRL_C_POLL: Duration = Duration::from_millis(50);

impl Feedback for Terminal {
    fn say(&mut self, line: &str) {
        self.lines.suspend(|| eprintln!("{line}"));
        if let Some(pacing) = &mut self.plain_live {
            pacing.restart();
        }
    }

    fn live(&mut self, line: &str) {
        if let Some(pacing) = &mut self.plain_live {
            if pacing.due(Instant::now()) {
                eprintln!("waiting: {line}");
            }
            return;
        }
        self.live.set_message(line.to_owned());
        self.live.tick();
    }

    fn progress(&mut self, samples: u32, total: u32) {
        let (lines, live) = (&self.lines, &self.live);
        let bar = self.bar.get_or_insert_with(|| {
            live.set_message("averaging: hold the board still");
            let bar = lines.add(ProgressBar::new(u64::from(total)));
            bar.set_style(
                ProgressStyle::with_template("averaging [{bar:40}] {pos}/{len} samples")
                    .unwrap_or_else(|_| ProgressStyle::default_bar()),
            );
            bar
        });
        bar.set_position(u64::from(samples));
    }

    fn progress_done(&mut self) {
        if let Some(bar) = self.bar.take() {
            bar.finish_and_clear();
        }
    }

    fn confirm(&mut self, question: &str) -> bool {
        if self.assume_yes {
            return true;
        }
        if !std::io::stdin().is_terminal() {
            self.say(&format!("{question} no (not a terminal; pass --yes to accept)"));
            return false;
        }
        self.ask(question)
    }
}

impl Drop for Terminal {
    fn drop(&mut self) {
        self.live.finish_and_clear();
    }
}

/// Feedback for a command: none with `--json`, else the terminal.
pub fn feedback(json: bool, yes: bool) -> Box<dyn Feedback> {
    if json {
        Box::new(Silent { yes })
    } else {
        Box::new(Terminal::new(yes))
    }
}

/// A bar on stderr counting `len` steps, drawn by `template` (indicatif's); clear it with
/// `finish_and_clear`.
pub fn counting(template: &str, len: u64) -> ProgressBar {
    let style = ProgressStyle::with_template(template).unwrap_or_else(|_| ProgressStyle::default_bar());
    ProgressBar::new(len).with_style(style)
}

/// A spinner on stderr with the time so far, for work of unknown length that can take seconds (drawn
/// only where stderr is a terminal); clear it with `finish_and_clear`.
pub fn working(message: String) -> ProgressBar {
    let spinner = ProgressBar::new_spinner();
    let style = ProgressStyle::with_template("{spinner} {msg} ({elapsed})")
        .unwrap_or_else(|_| ProgressStyle::default_spinner());
    spinner.set_style(style);
    spinner.set_message(message);
    spinner.enable_steady_tick(std::time::Duration::from_millis(100));
    spinner
}

/// Exit status when whoever read the output went away (`| head`): 128 + SIGPIPE, what a shell
/// reports for a Unix tool that a closed pipe ended.
pub const READER_GONE_EXIT: i32 = 141;

/// Ends the process at once, with [`READER_GONE_EXIT`] and no message, when printing to standard
/// output fails because its reader closed the pipe: `println!` panics then, which is no fault of
/// the command's. Every file a command writes is written before it prints, and a session file
/// after each capture, so nothing is lost that was not already going to the closed pipe.
// NOTE: Rust ignores SIGPIPE so that a write fails instead; restoring the signal's default would
// also end the process silently when a child it pipes to (the emulated Pico) dies, which must be
// named instead.
pub fn end_quietly_when_the_reader_goes_away() {
    let default = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let message = info.payload_as_str().unwrap_or_default();
        if message.starts_with("failed printing to stdout") && message.contains("Broken pipe") {
            std::process::exit(READER_GONE_EXIT);
        }
        default(info);
    }));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_drawn_nowhere_is_written_every_ten_seconds_of_a_wait_and_not_for_a_short_one() {
        let start = Instant::now();
        let at = |s: f64| start + Duration::from_secs_f64(s);
        let mut pacing = Pacing::new(PLAIN_LIVE_EVERY);
        let lines = [0.0, 0.5, 9.9, 10.0, 12.0, 19.9, 20.1, 25.0];
        let written: Vec<f64> = lines.into_iter().filter(|&s| pacing.due(at(s))).collect();
        assert_eq!(written, [10.0, 20.1]);
        pacing.restart();
        let after_instruction: Vec<f64> = [21.0, 30.9, 31.0].into_iter().filter(|&s| pacing.due(at(s))).collect();
        assert_eq!(after_instruction, [31.0], "a new instruction's wait is counted from its own first line");
    }
}
