"""Breaks, one at a time, each line whose mistake issue 22 found no test to catch, and checks that the
test written for it now fails; restores the line after each run.

Usage: python3 host/tools/guarded_mutations.py [WORDS...]   (only the changes whose name holds a word)
Exits 1 when a change is no longer found in the code (update its line here with the code) or when a
test stays green with it (the guard is gone). Run from the repository root; it runs `cargo test`.
"""
import pathlib
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parent.parent.parent
# The crates whose lines are broken: the I/O-free core, then the host (a file lives in one of them).
CRATES = [("accelcal-core", ROOT / "core" / "src"), ("accelcal", ROOT / "host" / "src")]


def source_file(rel):
    """The crate source file `rel` names (core first, then host)."""
    return next((src / rel for _, src in CRATES if (src / rel).exists()), CRATES[-1][1] / rel)


def crate_of(test):
    """The crate whose unit tests hold `test`: the one with a file for the test's module."""
    parts = test.split("::")[:-2]
    for name, src in CRATES:
        base = src.joinpath(*parts)
        if base.with_suffix(".rs").exists() or (base / "mod.rs").exists():
            return name
    return CRATES[-1][0]

# (what the change does to a user, file, the line as it is, the line broken, the tests that must fail)
CHANGES = [
    ("a long noise-report capture limit is not held to the longest capture", "procedure/stop_rule.rs",
     "capture_limit_s.unwrap_or(MAX_CAPTURE_SECONDS).clamp(MIN_CAPTURE_SECONDS, MAX_CAPTURE_SECONDS)",
     "capture_limit_s.unwrap_or(MAX_CAPTURE_SECONDS)",
     "procedure::stop_rule::tests::a_noise_report_capture_limit_is_held_within_the_shortest_and_longest_capture"),
    ("a capture limit under the shortest capture is let through (a panic in clamp)", "procedure/stop_rule.rs",
     "capture_limit_s.unwrap_or(MAX_CAPTURE_SECONDS).clamp(MIN_CAPTURE_SECONDS, MAX_CAPTURE_SECONDS)",
     "capture_limit_s.unwrap_or(MAX_CAPTURE_SECONDS).max(MIN_CAPTURE_SECONDS)",
     "procedure::stop_rule::tests::a_noise_report_capture_limit_is_held_within_the_shortest_and_longest_capture"),
    ("a session resumes at another filter", "session/board.rs",
     "(self.config.range, self.config.filter) != (board.config.range, board.config.filter)",
     "self.config.range != board.config.range",
     "session::board::tests::a_session_resumes_only_on_its_board_at_its_range_and_filter"),
    ("the verification's worst error ignores readings below 1 g", "session/verification.rs",
     "m.max(c.after_mg.abs())", "m.max(c.after_mg)",
     "procedure::verify::tests::the_worst_error_counts_readings_below_1_g_as_well_as_above"),
    ("the random walk K 18 % low", "noise/fit.rs",
     "FLICKER_FLOOR * FLICKER_FLOOR, tau_s / 3.0)", "FLICKER_FLOOR * FLICKER_FLOOR, tau_s / 2.0)",
     "noise::fit::tests::an_exact_curve_gives_back_its_terms"),
    ("G's standard errors 25 % small", "fit/gyro/solve.rs",
     "(2 * turns.len()).saturating_sub(9)", "(3 * turns.len()).saturating_sub(9)",
     "fit::gyro::tests::the_standard_errors_of_g_match_its_scatter_over_repeated_sessions"),
    ("each turn's residual with G transposed", "fit/gyro/summary.rs",
     "Matrix3::from(*g).transpose()", "Matrix3::from(*g)",
     "fit::gyro::tests::a_turn_s_residual_with_the_true_g_is_nil_and_without_it_shows_the_scale_error"),
    ("the report's refit calibrates the positions with the drift left in", "report/session.rs",
     "None => fitted.rows.iter().map(|row| linalg::mul_vec(matrix, linalg::sub(row.reading, *offset))).collect(),",
     "None => session.captures.iter().map(|c| linalg::mul_vec(matrix, "
     "linalg::sub(c.stats.mean_g.map(f64::from), *offset))).collect(),",
     "report::session::tests::an_adaptive_session_s_positions_are_shown_with_the_drift_taken_out"),
    ("an adaptive session's drift is not fitted", "session/outcome.rs",
     "let drift = drift::fitted(&captures);",
     "let drift = None;",
     "report::session::tests::an_adaptive_session_s_positions_are_shown_with_the_drift_taken_out"),
    ("the uploaded record calibrates the positions without its temperature model", "report/uploaded.rs",
     "calibrate(c.stats.mean_g, c.stats.temp_c)", "calibrate(c.stats.mean_g, session.captures[0].stats.temp_c)",
     "report::session::tests::a_session_s_uploaded_record_is_shown_and_calibrates_its_positions"),
    ("the thermal held-out error 1.73x", "fit/thermal.rs",
     "(squares / 3.0).sqrt()", "squares.sqrt()",
     "fit::thermal::tests::the_held_out_error_of_noisy_readings_is_their_noise_per_axis"),
    ("Allan confidence bands narrow: edf over m, not 2m", "noise/allan.rs",
     "/ (2.0 * m)", "/ m",
     "noise::allan::tests::deviations_and_confidence_intervals_agree_with_allantools"),
    ("Allan confidence bands: edf's 4m^2 + 5 as 4m^2 + 1", "noise/allan.rs",
     "(4.0 * m * m + 5.0)", "(4.0 * m * m + 1.0)",
     "noise::allan::tests::deviations_and_confidence_intervals_agree_with_allantools"),
    ("Allan confidence bands: the wrong tail", "noise/allan.rs",
     "let tail = (1.0 - CONFIDENCE) / 2.0;", "let tail = (1.0 - CONFIDENCE) / 1.5;",
     "noise::allan::tests::deviations_and_confidence_intervals_agree_with_allantools"),
    ("an adaptive session ends from nine positions", "limits/procedure.rs",
     "const MIN_ADAPTIVE_POSITIONS: usize = 10;", "const MIN_ADAPTIVE_POSITIONS: usize = 9;",
     "procedure::adaptive::tests::a_prediction_ends_the_session_only_from_ten_positions_on"),
    ("the simulated clock makes up a stall in one jump", "sim/clock.rs",
     "u64::try_from(elapsed).unwrap_or(u64::MAX).min(MAX_REAL_STEP_US)", "u64::try_from(elapsed).unwrap_or(u64::MAX)",
     "sim::clock::tests::real_time_follows_the_wall_clock_and_stands_still_while_held"),
]


def caught(name, rel, line, broken, test):
    """Whether `test` fails with `line` broken; None when the line is not in the code once."""
    path = source_file(rel)
    text = path.read_text()
    if text.count(line) != 1:
        print(f"NOT FOUND  {name}: {rel} holds the line {text.count(line)} times", flush=True)
        return None
    path.write_text(text.replace(line, broken))
    try:
        started = time.monotonic()
        run = subprocess.run(["cargo", "test", "-q", "-p", crate_of(test), "--lib", "--", "--exact", test],
                             capture_output=True, text=True)
        output = run.stdout + run.stderr
        if "error[" in output or "running 1 test" not in output:
            print(f"NOT RUN    {name}: the broken code did not build or the test is gone\n{output[-2000:]}")
            return None
        verdict = "caught" if run.returncode else "GREEN"
        print(f"{verdict:<10} {name} ({rel}; {test}; {time.monotonic() - started:.0f} s)", flush=True)
        return run.returncode != 0
    finally:
        path.write_text(text)


def main():
    words = sys.argv[1:]
    chosen = [c for c in CHANGES if not words or any(w in c[0] for w in words)]
    results = [caught(*change) for change in chosen]
    good = sum(r is True for r in results)
    print(f"{good} of {len(chosen)} logic changes caught by their tests")
    sys.exit(0 if good == len(chosen) else 1)


if __name__ == "__main__":
    main()
