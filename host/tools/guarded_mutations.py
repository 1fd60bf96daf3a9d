"""Breaks, one at a time, each line whose mistake once went past every test (issue 22, issue 36), and checks that
the test written for it now fails; docs/mutations.md tables them.

Each line is a `mutant!("name", original, broken)` in the core's or the host's source (core/src/mutant.rs): the test
binaries of both crates are built once with their `mutants` feature, and each guard test is run on its own with `ACCELCAL_MUTANT=name`, which picks
the broken expression. No source file is ever written, so a run killed halfway leaves the tree as it was.

Usage: python3 host/tools/guarded_mutations.py [WORDS...]   (only the changes whose name or words hold a word)
Exits 1 when a named mutation is not in the source exactly once (in the file listed here), when a guard test fails
with no mutation active, or when a guard test stays green with its mutation (the guard is gone). Run from anywhere;
it runs `cargo test --no-run` in the target directory cargo would use (CARGO_TARGET_DIR is honoured).
"""
import functools
import json
import os
import pathlib
import re
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parent.parent.parent
HOST = ROOT / "host"
# The crates whose lines are broken, each with its source root: a listed file is in one of them.
CRATES = {"accelcal-core": ROOT / "core" / "src", "accelcal": HOST / "src"}
VARIABLE = "ACCELCAL_MUTANT"
# NOTE: a mutation may make its test loop forever; such a test did not pass, and the run goes on.
TIMEOUT_S = 900
LIB = "lib"

# (name in mutant!, what the change does to a user, file (under core/src or host/src), the test that must
# fail[, test binary: "lib" (the unit tests of the crate that holds the test's module) or a host/tests target])
CHANGES = [
    # Issue 22's: each line once no test caught.
    ("stop-rule-no-upper-clamp", "a long noise-report capture limit is not held to the longest capture",
     "run/stop_rule.rs",
     "run::stop_rule::tests::a_noise_report_capture_limit_is_held_within_the_shortest_and_longest_capture"),
    ("stop-rule-no-lower-clamp", "a capture limit under the shortest capture is let through (a panic in clamp)",
     "run/stop_rule.rs",
     "run::stop_rule::tests::a_noise_report_capture_limit_is_held_within_the_shortest_and_longest_capture"),
    ("resume-other-filter", "a session resumes at another filter", "session/board.rs",
     "session::board::tests::a_session_resumes_only_on_its_board_at_its_range_and_filter"),
    ("worst-error-signed", "the verification's worst error ignores readings below 1 g", "session/verification.rs",
     "run::verify::tests::the_worst_error_counts_readings_below_1_g_as_well_as_above"),
    ("random-walk-tau-2", "the random walk K 18 % low", "noise/fit.rs",
     "noise::fit::tests::an_exact_curve_gives_back_its_terms"),
    ("gyro-dof-3n", "G's standard errors 25 % small", "fit/gyro/solve.rs",
     "fit::gyro::tests::the_standard_errors_of_g_match_its_scatter_over_repeated_sessions"),
    ("gyro-residual-g-untransposed", "each turn's residual with G transposed", "fit/gyro/summary.rs",
     "fit::gyro::tests::a_turn_s_residual_with_the_true_g_is_nil_and_without_it_shows_the_scale_error"),
    ("report-refit-drift-left-in", "the report's refit calibrates the positions with the drift left in",
     "report/session.rs",
     "report::session::tests::an_adaptive_session_s_positions_are_shown_with_the_drift_taken_out"),
    ("adaptive-drift-unfitted", "an adaptive session's drift is not fitted", "session/outcome.rs",
     "report::session::tests::an_adaptive_session_s_positions_are_shown_with_the_drift_taken_out"),
    ("uploaded-first-temperature", "the uploaded record calibrates the positions without its temperature model",
     "report/uploaded.rs",
     "report::session::tests::a_session_s_uploaded_record_is_shown_and_calibrates_its_positions"),
    ("thermal-held-out-unscaled", "the thermal held-out error 1.73x", "fit/thermal.rs",
     "fit::thermal::tests::the_held_out_error_of_noisy_readings_is_their_noise_per_axis"),
    ("allan-edf-over-m", "Allan confidence bands narrow: edf over m, not 2m", "noise/allan.rs",
     "noise::allan::tests::deviations_and_confidence_intervals_agree_with_allantools"),
    ("allan-edf-plus-1", "Allan confidence bands: edf's 4m^2 + 5 as 4m^2 + 1", "noise/allan.rs",
     "noise::allan::tests::deviations_and_confidence_intervals_agree_with_allantools"),
    ("allan-wrong-tail", "Allan confidence bands: the wrong tail", "noise/allan.rs",
     "noise::allan::tests::deviations_and_confidence_intervals_agree_with_allantools"),
    ("adaptive-ends-from-nine", "an adaptive session ends from nine positions", "run/adaptive.rs",
     "run::adaptive::tests::a_prediction_ends_the_session_only_from_ten_positions_on"),
    ("sim-clock-one-jump", "the simulated clock makes up a stall in one jump", "sim/clock.rs",
     "sim::clock::tests::real_time_follows_the_wall_clock_and_stands_still_while_held"),
    # Issue 36's: fresh one-line mutations, each caught by the test named.
    ("ardupilot-tcal-shift-sign", "ArduPilot's TCAL coefficients re-expanded about the wrong side of 35 degC",
     "export/flight.rs",
     "export::flight::tests::ardupilot_s_tcal_takes_out_the_model_s_drift_in_m_s2_and_rad_s_at_every_temperature"),
    ("ardupilot-tcal-in-g", "ArduPilot's accelerometer TCAL coefficients in g, not m/s^2 (9.8x too small)",
     "export/flight.rs",
     "export::flight::tests::ardupilot_s_tcal_takes_out_the_model_s_drift_in_m_s2_and_rad_s_at_every_temperature"),
    ("px4-tc-order-shifted", "PX4's TC_A0/TC_G0 X1-X3 each take the next order's coefficient", "export/flight.rs",
     "export::flight::tests::px4_s_thermal_offsets_are_the_model_s_drift_in_m_s2_and_rad_s_at_every_temperature"),
    ("px4-tc-gyro-in-deg", "PX4's gyro thermal coefficients in deg/s, not rad/s (57x)", "export/flight.rs",
     "export::flight::tests::px4_s_thermal_offsets_are_the_model_s_drift_in_m_s2_and_rad_s_at_every_temperature"),
    ("i2cdevlib-gyro-sign", "the i2cdevlib gyro offset lines add the bias instead of taking it out",
     "export/i2cdevlib.rs",
     "export::i2cdevlib::tests::the_gyro_offset_lines_add_minus_the_bias_in_the_register_s_counts"),
    ("adafruit-gyro-in-deg", "Adafruit's gyro_zerorate in deg/s, not rad/s", "export/adafruit.rs",
     "export::adafruit::tests::the_json_s_gyro_zero_rate_is_the_bias_in_rad_per_s"),
    ("multiwii-offset-sign", "Betaflight's acc_calibration with the offset's sign turned", "export/multiwii.rs",
     "export::multiwii::tests::betaflight_s_acc_calibration_is_the_offset_in_its_counts"),
    ("fusion-offset-in-g", "Fusion's accelerometerOffset in g where its readings are counts", "export/fusion.rs",
     "export::fusion::tests::fusion_s_offsets_are_the_biases_in_counts"),
    ("fusion-gyro-offset-sign", "Fusion's gyroscopeOffset with the bias's sign turned", "export/fusion.rs",
     "export::fusion::tests::fusion_s_offsets_are_the_biases_in_counts"),
    ("export-loss-rms-unmeaned", "an export's stated RMS loss is a root of the sum, not of the mean", "export/loss.rs",
     "export::loss::tests::offsets_only_leave_the_scale_error_of_an_axis_analytically"),
    ("stream-single-lost-uncounted", "a stream's single lost sample is not counted", "stream/timing.rs",
     "stream::timing::tests::a_single_lost_sample_is_counted_alone_and_after_another"),
    ("dropped-lines-counted-once", "the dropped lines of a reason counted as one however many", "stream/dropped.rs",
     "stream::log::tests::bad_bytes_and_impossible_values_are_dropped_lines_and_cost_no_period_and_no_loss"),
    ("stream-counts-4g-as-2g", "a stream in +-4 g counts read as 16384 a g (half its size)", "stream/units.rs",
     "stream::units::tests::a_stream_s_counts_are_read_at_the_datasheet_s_sensitivity_of_their_range"),
    ("stream-gyro-1000-rounded", "a stream's +-1000 deg/s counts read at 33 a deg/s (0.6 % slow)", "stream/units.rs",
     "stream::units::tests::a_stream_s_counts_are_read_at_the_datasheet_s_sensitivity_of_their_range"),
    ("cost-here-time-doubled", "the cost line's capture time at the sketch's rate doubled", "stream/cost.rs",
     "stream::cost::tests::a_stream_s_aliasing_cost_names_its_band_and_both_capture_times"),
    ("cost-low-pass-above-nyquist", "the cost line names a low-pass above the Nyquist frequency (94 Hz at 100 Hz)",
     "stream/cost.rs",
     "stream::cost::tests::a_stream_s_aliasing_cost_names_its_band_and_both_capture_times"),
    ("cost-filtered-time-unhalved", "the cost line's time behind the low-pass doubled", "stream/cost.rs",
     "stream::cost::tests::a_stream_s_aliasing_cost_names_its_band_and_both_capture_times"),
    ("cost-gyro-bias-whole-step", "the gyro's printed step claimed as its bias uncertainty, not half of it",
     "stream/cost.rs",
     "stream::cost::tests::a_gyro_printed_in_tenths_is_known_to_half_a_tenth"),
    ("cost-lost-one-short", "the cost line's lost samples one short", "stream/cost.rs",
     "stream::cost::tests::the_samples_lost_in_gaps_are_counted_in_the_cost_line"),
    ("family-lookalike-unconfirmed", "a look-alike whose offsets confirm the family it runs as is not confirmed",
     "part/check.rs",
     "part::check::tests::a_look_alike_whose_offsets_confirm_the_family_it_runs_as_is_confirmed_whatever_its_who_am_i"),
    # Issue 36's run policies, each a unit test of the core.
    ("resume-drops-earlier-g", "a resumed run without turns uploads without the G it uploaded before", "run/resume.rs",
     "run::resume::tests::a_resumed_run_without_turns_keeps_an_earlier_upload_s_g_or_says_why_it_has_none"),
    ("resume-claims-board-time", "a resumed run claims board time from a capture of an earlier run", "run/resume.rs",
     "run::resume::tests::a_resumed_run_claims_no_board_time_and_a_first_run_claims_its_first_capture_s"),
    ("kept-before-verifying-without-upload", "a Ctrl-C during the verification leaves a session without the upload",
     "run/resume.rs", "run::resume::tests::the_session_kept_before_verifying_holds_the_upload_and_every_capture"),
    ("stream-ctrl-c-certified", "a stream session stopped by Ctrl-C is certified as complete", "run/ending.rs",
     "run::ending::tests::a_run_stopped_by_ctrl_c_is_not_complete_so_gets_no_certificate"),
    ("lot-std-population", "the lot's std over n, not n - 1 (small lots look tighter)", "lot/summary.rs",
     "lot::tests::the_summary_states_each_parameter_s_spread_and_the_boards_outside_the_limits"),
    ("lot-cpk-below-sign", "the lot's Cpk against a low limit with its sign turned", "lot/summary.rs",
     "lot::tests::cpk_is_the_distance_to_the_nearer_limit_in_three_standard_deviations"),
    ("lot-outside-inverted", "the lot lists the boards inside the limits as outside", "lot/summary.rs",
     "lot::tests::the_summary_states_each_parameter_s_spread_and_the_boards_outside_the_limits"),
    ("lot-text-one-boards", "a lot of one board says '1 boards'", "lot/text.rs",
     "lot::tests::the_summary_says_no_spec_was_given_rather_than_that_no_board_is_outside_it"),
    ("certificate-parameter-k1", "a certificate's parameters state U = u (k = 1) under k = 2", "certificate/mod.rs",
     "certificate::tests::every_expanded_uncertainty_is_twice_its_standard_uncertainty"),
    ("certificate-predicted-k1", "a certificate's predicted errors state U = u (k = 1)", "certificate/mod.rs",
     "certificate::tests::every_expanded_uncertainty_is_twice_its_standard_uncertainty"),
    ("verdict-missed-within-noise", "a target missed by less than the noise floor is called missed",
     "session/verdict.rs",
     "session::verdict::tests::a_verification_reaches_misses_or_stays_within_its_noise_of_the_target"),
    ("verdict-trusted-ten-floors", "a calibration 10 noise floors out is called trusted", "session/verdict.rs",
     "session::verdict::tests::a_verification_reaches_misses_or_stays_within_its_noise_of_the_target"),
    ("verdict-reached-by-the-floor", "a target missed by up to one noise floor is called reached", "session/verdict.rs",
     "session::verdict::tests::a_verification_reaches_misses_or_stays_within_its_noise_of_the_target"),
    ("selftest-attempts-plural", "a self-test of one attempt says it was repeated", "selftest/report.rs",
     "selftest::tests::the_text_shows_the_previous_deviation_beside_each_axis_and_the_family_verdict_beside_accelcals"),
]


def mutants_in_source():
    """Each mutant!'s name and the files it is in (relative to its crate's source root), once per use."""
    found = {}
    for src in CRATES.values():
        for path in sorted(src.rglob("*.rs")):
            code = "\n".join(line for line in path.read_text().splitlines() if not line.lstrip().startswith("//"))
            for name in re.findall(r'mutant!\(\s*"([^"]+)"', code):
                found.setdefault(name, []).append(str(path.relative_to(src)))
    return found


@functools.lru_cache(maxsize=None)
def crate_of(test):
    """The crate whose unit tests hold `test`: the one whose source defines the test's function (the
    core and the host both have modules such as `selftest`, so the module path alone cannot tell)."""
    function = f"fn {test.rsplit('::', 1)[-1]}("
    for name, src in CRATES.items():
        if any(function in path.read_text() for path in src.rglob("*.rs")):
            return name
    return "accelcal"


def placed(chosen):
    """Whether every chosen mutation is in its file, once, and nowhere else; says which is not."""
    found, good = mutants_in_source(), True
    for name, _, rel, *_ in chosen:
        if found.get(name) != [rel]:
            print(f"NOT FOUND  {name}: in {found.get(name, [])}, where once in {rel} is wanted", flush=True)
            good = False
    listed = {c[0] for c in CHANGES}
    for name in sorted(set(found) - listed):
        print(f"UNLISTED   {name}: in {found[name]} but not listed here", flush=True)
        good = False
    return good


def binary_of(change):
    """The test binary of a change: (crate, "lib") for unit tests, ("accelcal", NAME) for host/tests/NAME.rs."""
    return ("accelcal", change[4]) if len(change) > 4 else (crate_of(change[3]), LIB)


def build(binaries):
    """Builds the test binaries once with both crates' mutants feature; their paths by (crate, binary)."""
    features = ",".join(f"{crate}/mutants" for crate in CRATES)
    command = ["cargo", "test", "--features", features, "--no-run", "--message-format=json"]
    command += [arg for crate in CRATES for arg in ("-p", crate)]
    if any(binary == LIB for _, binary in binaries):
        command += ["--lib"]
    command += [arg for _, binary in sorted(binaries) if binary != LIB for arg in ("--test", binary)]
    run = subprocess.run(command, cwd=ROOT, capture_output=True, text=True)
    paths = {}
    for line in run.stdout.splitlines():
        message = json.loads(line) if line.startswith("{") else {}
        if message.get("reason") != "compiler-artifact" or not message.get("executable"):
            continue
        manifest = pathlib.Path(message.get("manifest_path", ""))
        crate = next((name for name, src in CRATES.items() if manifest == src.parent / "Cargo.toml"), None)
        if not message["profile"]["test"] or crate is None:
            continue
        target = message["target"]
        paths[(crate, LIB if "lib" in target["kind"] else target["name"])] = message["executable"]
    if run.returncode != 0 or not set(binaries) <= set(paths):
        print(f"NOT BUILT  the test binaries with --features {features}\n{run.stderr[-3000:]}", flush=True)
        return None
    return paths


def run_test(binary, executable, test, mutation):
    """Runs one test on its own; (passed, ran, seconds), passed False when it timed out."""
    env = {k: v for k, v in os.environ.items() if k != VARIABLE}
    if mutation:
        env[VARIABLE] = mutation
    started = time.monotonic()
    try:
        # NOTE: in its crate's folder, as `cargo test` runs it.
        run = subprocess.run([executable, "--exact", test], cwd=CRATES[binary[0]].parent, env=env, capture_output=True, text=True,
                             timeout=TIMEOUT_S)
    except subprocess.TimeoutExpired:
        return False, True, time.monotonic() - started
    ran = "running 1 test" in run.stdout
    return run.returncode == 0, ran, time.monotonic() - started


def guards_pass(chosen, paths):
    """Whether every guard test passes with no mutation active (else a red guard proves nothing)."""
    good = True
    for binary, test in sorted({(binary_of(c), c[3]) for c in chosen}):
        passed, ran, seconds = run_test(binary, paths[binary], test, None)
        if not (passed and ran):
            why = "fails with no mutation active" if ran else "is not in the binary"
            print(f"BROKEN     {test} ({binary}) {why} ({seconds:.1f} s)", flush=True)
            good = False
    return good


def caught(change, paths):
    """Whether the change's test fails with its mutation active; None when the test did not run."""
    name, words, rel, test = change[:4]
    passed, ran, seconds = run_test(binary_of(change), paths[binary_of(change)], test, name)
    if not ran:
        print(f"NOT RUN    {name}: {test} is not in the binary", flush=True)
        return None
    verdict = "GREEN" if passed else "caught"
    print(f"{verdict:<10} {name}: {words} ({rel}; {test}; {seconds:.1f} s)", flush=True)
    return not passed


def main():
    started = time.monotonic()
    words = sys.argv[1:]
    chosen = [c for c in CHANGES if not words or any(w in c[0] or w in c[1] for w in words)]
    ready = placed(chosen)
    paths = build({binary_of(c) for c in chosen})
    if paths is None:
        sys.exit(1)
    print(f"built once with --features mutants ({time.monotonic() - started:.0f} s)", flush=True)
    ready = guards_pass(chosen, paths) and ready
    results = [caught(change, paths) for change in chosen]
    good = sum(r is True for r in results)
    print(f"{good} of {len(chosen)} logic changes caught by their tests ({time.monotonic() - started:.0f} s in all)")
    sys.exit(0 if good == len(chosen) and ready else 1)


if __name__ == "__main__":
    main()
