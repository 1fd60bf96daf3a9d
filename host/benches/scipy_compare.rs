//! ortho9 next to scipy.optimize.least_squares(method='lm') and Ceres on the same 24-position
//! problems, timed side by side in one run: `cargo bench -p accelcal --bench scipy_compare`.
//!
//! scipy needs python3 with numpy and scipy; Ceres needs g++ and Debian's libceres-dev (the bench
//! builds benches/ceres_ortho9.cc itself). Either missing is said and skipped; the rest still runs.
//! Every solver starts from M = I, o = 0 on readings in g with tolerances of 1e-12 and an analytic
//! Jacobian. Like for like is the solve alone (`shared::ortho9::fit`); accelcal's whole fit adds the
//! normalisation, the conditioning check and the statistics, and is timed too.

use std::io::Write;
use std::path::PathBuf;
use std::process::{Command, Stdio};
use std::time::Instant;

use accelcal::fit::Model;
use accelcal::fit::{self, FitOptions, ModelChoice};
use accelcal::sim::synthetic::random_positions;

const PROBLEMS: u64 = 200;
const POSITIONS: usize = 24;
const REPEATS: usize = 5;

/// A solver's best-of-repeats time for all problems and its cost per problem.
struct Run {
    seconds: f64,
    costs: Vec<f64>,
}

fn main() {
    let problems: Vec<_> = (0..PROBLEMS).map(|seed| random_positions(1000 + seed, POSITIONS, 1e-4, false)).collect();
    let readings: Vec<Vec<[f64; 3]>> = problems.iter().map(|p| p.rows.iter().map(|r| r.reading).collect()).collect();
    let choice = ModelChoice::Only(Model::Ortho9);
    let options = FitOptions::default();
    let whole =
        best_of(|| problems.iter().map(|p| fit::fit(p, choice, &options).map_or(f64::NAN, |f| f.cost)).collect());
    let solve = best_of(|| readings.iter().map(|r| shared::ortho9::fit(r).map_or(f64::NAN, |f| f.cost)).collect());
    println!("{PROBLEMS} problems of {POSITIONS} positions, best of {REPEATS}, per problem:");
    println!("  accelcal shared ortho9 solver      {:8.2} us", per_problem_us(&solve));
    println!("  accelcal whole fit (+ statistics)  {:8.2} us", per_problem_us(&whole));
    match scipy(&readings) {
        Ok(scipy) => compare("scipy least_squares", &scipy, &solve, &whole),
        Err(why) => println!("scipy comparison skipped: {why}"),
    }
    match ceres(&readings) {
        Ok(runs) => report_ceres(runs, &solve, &whole),
        Err(why) => println!("Ceres comparison skipped: {why}"),
    }
}

/// Prints each Ceres solver's time and compares with the fastest.
fn report_ceres(runs: Vec<(String, Run)>, solve: &Run, whole: &Run) {
    for (name, run) in &runs {
        println!("  Ceres {name:28} {:8.2} us", per_problem_us(run));
    }
    let fastest = runs.into_iter().map(|(_, run)| run).min_by(|a, b| a.seconds.total_cmp(&b.seconds));
    fastest.iter().for_each(|ceres| compare("Ceres", ceres, solve, whole));
}

/// The best of [`REPEATS`] timed runs of `fit_all`.
fn best_of(mut fit_all: impl FnMut() -> Vec<f64>) -> Run {
    let mut run = Run { seconds: f64::INFINITY, costs: Vec::new() };
    for _ in 0..REPEATS {
        let began = Instant::now();
        run.costs = std::hint::black_box(fit_all());
        run.seconds = run.seconds.min(began.elapsed().as_secs_f64());
    }
    run
}

fn per_problem_us(run: &Run) -> f64 {
    run.seconds / PROBLEMS as f64 * 1e6
}

/// Prints the speedups over `other` and the largest relative cost difference.
fn compare(name: &str, other: &Run, solve: &Run, whole: &Run) {
    println!("  {name:34} {:8.2} us", per_problem_us(other));
    println!("ortho9 fit speedup vs {name}: {:.1}x", other.seconds / solve.seconds);
    println!("ortho9 whole fit (with statistics) speedup vs {name}: {:.1}x", other.seconds / whole.seconds);
    // Positive: ours is higher (worse); negative: ours is lower.
    let worst = solve.costs.iter().zip(&other.costs).map(|(ours, theirs)| (ours - theirs) / theirs);
    println!(
        "largest relative cost difference (accelcal - {name}) / {name}: {:+.2e}",
        worst.fold(f64::NEG_INFINITY, f64::max)
    );
}

/// Runs benches/scipy_ortho9.py on the problems.
fn scipy(readings: &[Vec<[f64; 3]>]) -> Result<Run, String> {
    let input = serde_json::json!({ "problems": readings }).to_string();
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/benches/scipy_ortho9.py");
    let output =
        run_with_input(Command::new("python3").arg(script), &input).map_err(|e| format!("cannot run python3 ({e})"))?;
    let parsed = serde_json::from_slice::<serde_json::Value>(&output)
        .map_err(|_| "python3 with numpy and scipy is needed (pip install numpy scipy)".to_owned())?;
    let seconds = parsed["seconds"].as_f64().ok_or("the script printed no time")?;
    let costs =
        parsed["costs"].as_array().ok_or("the script printed no costs")?.iter().filter_map(|c| c.as_f64()).collect();
    Ok(Run { seconds, costs })
}

/// Builds benches/ceres_ortho9.cc with g++ and runs it on the problems: one run per dense solver.
fn ceres(readings: &[Vec<[f64; 3]>]) -> Result<Vec<(String, Run)>, String> {
    let program = build_ceres()?;
    let mut input = format!("{}\n", readings.len());
    for problem in readings {
        input += &format!("{}\n", problem.len());
        problem.iter().for_each(|m| input += &format!("{:.17e} {:.17e} {:.17e}\n", m[0], m[1], m[2]));
    }
    let output =
        run_with_input(&mut Command::new(&program), &input).map_err(|e| format!("cannot run {program:?} ({e})"))?;
    let text = String::from_utf8_lossy(&output);
    text.lines()
        .map(parse_ceres_line)
        .collect::<Option<Vec<_>>>()
        .filter(|runs| !runs.is_empty())
        .ok_or(format!("unreadable output: {text}"))
}

fn parse_ceres_line(line: &str) -> Option<(String, Run)> {
    let mut fields = line.split_whitespace();
    let name = fields.next()?.to_owned();
    let seconds = fields.next()?.parse().ok()?;
    let costs = fields.map(|c| c.parse().unwrap_or(f64::NAN)).collect();
    Some((name, Run { seconds, costs }))
}

/// Compiles the Ceres program once per bench build into cargo's scratch directory.
fn build_ceres() -> Result<PathBuf, String> {
    let source = concat!(env!("CARGO_MANIFEST_DIR"), "/benches/ceres_ortho9.cc");
    let program = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("ceres_ortho9");
    let output = Command::new("g++")
        .args(["-O3", "-DNDEBUG", "-std=c++17", "-I/usr/include/eigen3", source, "-o"])
        .arg(&program)
        .args(["-lceres", "-lglog"])
        .output()
        .map_err(|e| format!("cannot run g++ ({e})"))?;
    if !output.status.success() {
        let first =
            String::from_utf8_lossy(&output.stderr).lines().find(|l| l.contains("error")).unwrap_or("").to_owned();
        return Err(format!("g++ could not build {source} against Ceres (apt-get install libceres-dev): {first}"));
    }
    Ok(program)
}

/// Runs `command` with `input` on stdin and returns its stdout.
fn run_with_input(command: &mut Command, input: &str) -> std::io::Result<Vec<u8>> {
    let mut child = command.stdin(Stdio::piped()).stdout(Stdio::piped()).stderr(Stdio::null()).spawn()?;
    child.stdin.take().expect("stdin is piped").write_all(input.as_bytes())?;
    Ok(child.wait_with_output()?.stdout)
}
