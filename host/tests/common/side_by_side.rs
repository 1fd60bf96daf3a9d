//! A harness for scenarios that wait on something running in real time (a simulated board over a
//! pseudo-terminal, a replayed stream): they use a few percent of a core all together, so they run
//! side by side, as many threads as scenarios, and take the time of the longest alone. The usual
//! filters, `--exact`, `--list` and the report are libtest-mimic's, as the standard harness's.

use libtest_mimic::{Arguments, Failed, Trial};

/// Runs `scenarios` (name, function), each on its own thread unless `--test-threads` says otherwise.
pub fn run(scenarios: Vec<(&'static str, fn())>) -> std::process::ExitCode {
    let mut arguments = Arguments::from_args();
    arguments.test_threads = arguments.test_threads.or(Some(scenarios.len()));
    let trials = scenarios.into_iter().map(|(name, scenario)| Trial::test(name, move || caught(scenario))).collect();
    libtest_mimic::run(&arguments, trials).exit_code()
}

/// A scenario's panic as the failure the report shows.
fn caught(scenario: fn()) -> Result<(), Failed> {
    std::panic::catch_unwind(scenario).map_err(|panic| {
        let message =
            panic.downcast_ref::<String>().cloned().or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()));
        Failed::from(message.unwrap_or_else(|| "panicked".to_owned()))
    })
}

/// The scenarios for [`run`], each named by its function.
// NOTE: allowed unused, as `#![allow(dead_code)]` allows the rest of `common`: each binary uses a part.
#[allow(unused_macros)]
macro_rules! scenarios {
    ($($scenario:ident),* $(,)?) => {
        vec![$((stringify!($scenario), $scenario as fn())),*]
    };
}
#[allow(unused_imports)]
pub(crate) use scenarios;
