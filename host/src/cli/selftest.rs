//! `accelcal selftest`: the datasheet self-test, beside the board's previous one.

use std::io::Write;

use shared::selftest::StoredSelfTest;

use super::args::SelftestArgs;
use crate::part::info::family_check;

use crate::error::Error;
use crate::selftest::history::{self, History, HistoryEntry};
use crate::selftest::report::SelfTestJson;
use crate::selftest::shown::Shown;
use crate::selftest::{run, PhaseName, Watcher};
use crate::session::BoardRecord;

/// What the procedure shows a person on stderr (nothing with `--json`).
struct Lines {
    quiet: bool,
}

impl Watcher for Lines {
    fn phase(&mut self, attempt: u8, phase: PhaseName) {
        if !self.quiet {
            eprintln!("attempt {attempt}: {} (1 s)", phase.label());
        }
    }

    fn moved(&mut self, attempt: u8, why: &str) {
        if !self.quiet {
            eprintln!("attempt {attempt}: the board moved ({why}); keep your hands off it, trying again");
        }
    }
}

/// `accelcal selftest (--port P | --sim) [--json] [--history DIR]`: exits 2 when an axis failed.
pub(super) fn selftest(args: &SelftestArgs) -> Result<(), Error> {
    let mut opened = args.device.open()?;
    let board = BoardRecord::of(&opened.connection.info);
    let history = history_of(args, &board.serial);
    let kept = match &history {
        Some(history) => history.entries()?.pop(),
        None => None,
    };
    // NOTE: the board's own is the latest wherever it ran; the file's is newer after a reflash.
    let previous = [board.self_test, kept].into_iter().flatten().max_by(|a, b| a.date_utc.cmp(&b.date_utc));
    if !args.json {
        eprintln!("rest the board on a table and keep your hands off it (about 3 s)");
    }
    let connection = &mut opened.connection;
    connection.client.interrupt_on(crate::terminal::interrupt_on_ctrl_c());
    let check = family_check(&mut connection.client, &connection.info)?;
    let test = run(&mut connection.client, &connection.info, &mut Lines { quiet: args.json })?;
    let result = SelfTestJson::of(&test);
    let shown = Shown { test: &test, result: &result, previous: previous.as_ref(), check: check.as_ref() };
    // NOTE: a reader that went away (`| head`) is no reason to lose the history entry after it.
    let _ = write!(std::io::stdout(), "{}", shown.output(args.json, history.as_ref().map(|h| h.path().to_path_buf())));
    if let Some(history) = &history {
        history.append(HistoryEntry::at(&result, crate::files::unix_time_s()))?;
    }
    let stored = StoredSelfTest { unix_time_s: crate::session::unix_time_s() as u32, raw: test.raw };
    connection.client.store_self_test(&stored)?;
    if test.passed() {
        Ok(())
    } else {
        Err(Error::SelfTestFailed)
    }
}

/// The board's history: in `--history`, or for a real board in the default folder.
fn history_of(args: &SelftestArgs, serial: &str) -> Option<History> {
    let dir = match (&args.history, args.device.sim) {
        (Some(dir), _) => Some(dir.clone()),
        (None, false) => history::default_dir(),
        (None, true) => None,
    };
    dir.map(|dir| History::of(&dir, serial))
}
