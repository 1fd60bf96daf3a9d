//! ortho9 next to its peers on the same 24-position problems, by CPU time, in one run:
//! `cargo bench -p accelcal --bench scipy_compare`. The peers: scipy.optimize.least_squares
//! (method='lm'), ceres::Solve, Ceres' fixed-size TinySolver and a plain fixed-size 9x9 Gauss-Newton
//! (the floor), the last three in benches/ortho9_peers.cc, which the bench builds with g++.
//!
//! scipy needs python3 with numpy and scipy; the C++ peers need g++ and Debian's libceres-dev. Either
//! missing is said and skipped; the rest still runs. Every solver starts from M = I, o = 0 on readings
//! in g with an analytic Jacobian and stops by the same rule: a step of at most tol (|x| + tol),
//! tol = `shared::ortho9::step_tolerance` (their other rules switched off). Each side's time is the
//! median of [`REPEATS`] runs over all problems, by CPU time (ours: this process's; theirs: the
//! child's own clock, python's `time.process_time`, C++'s CLOCK_PROCESS_CPUTIME_ID), single-threaded.

use std::io::Write;
use std::path::PathBuf;
use std::process::{Command, Stdio};

use accelcal::data::Dataset;
use accelcal::fit::Model;
use accelcal::fit::{self, FitOptions, ModelChoice};
use accelcal::sim::synthetic::random_positions;
use cpu_time::ProcessTime;

const PROBLEMS: u64 = 200;
const POSITIONS: usize = 24;
const REPEATS: usize = 7;
/// Noise of each averaged reading, in g.
const NOISE_G: f64 = 1e-4;
/// Samples each reading averaged (the same in every row, so the fit weighs them alike).
const SAMPLES: u32 = 1000;

/// One solver's median CPU time for all problems, its mean iterations and its cost per problem.
struct Run {
    name: String,
    seconds: f64,
    iterations: f64,
    costs: Vec<f64>,
}

fn main() {
    let problems: Vec<_> =
        (0..PROBLEMS).map(|seed| with_noise(random_positions(1000 + seed, POSITIONS, NOISE_G, false))).collect();
    let readings: Vec<Vec<[f64; 3]>> = problems.iter().map(|p| p.rows.iter().map(|r| r.reading).collect()).collect();
    let (choice, options) = (ModelChoice::Only(Model::Ortho9), FitOptions::default());
    let solve = median_of("accelcal shared::ortho9 (the solve)", || {
        readings
            .iter()
            .map(|r| shared::ortho9::fit(r).map_or((f64::NAN, 0), |f| (f.cost, f.iterations as usize)))
            .collect()
    });
    let whole = median_of("accelcal whole fit (statistics, noise test, prediction)", || {
        problems
            .iter()
            .map(|p| fit::fit(p, choice, &options).map_or((f64::NAN, 0), |f| (f.cost, f.iterations)))
            .collect()
    });
    let complete = problems.iter().filter_map(|p| fit::fit(p, choice, &options).ok());
    let complete = complete.filter(|f| f.noise_test.is_some() && f.prediction.is_some()).count();
    println!("whole fits with their noise test and prediction: {complete} of {PROBLEMS}");
    let mut peers = Vec::new();
    match scipy(&readings) {
        Ok(run) => peers.push(run),
        Err(why) => println!("scipy comparison skipped: {why}"),
    }
    match cpp_peers(&readings) {
        Ok(runs) => peers.extend(runs),
        Err(why) => println!("Ceres and Gauss-Newton comparison skipped: {why}"),
    }
    report(&solve, &whole, &peers);
}

/// The rows as captures state them, `count` and `std_*` (the noise of their mean is [`NOISE_G`]): the
/// whole fit then computes everything a session's fit does, the noise test and the noise's errors too.
fn with_noise(mut problem: Dataset) -> Dataset {
    for row in &mut problem.rows {
        row.count = Some(SAMPLES);
        row.std = Some([NOISE_G * f64::from(SAMPLES).sqrt(); 3]);
    }
    problem
}

/// Prints every solver's time per problem and iterations, then the ratios and cost agreement.
fn report(solve: &Run, whole: &Run, peers: &[Run]) {
    println!("{PROBLEMS} problems of {POSITIONS} positions, median of {REPEATS} runs, CPU time per problem:");
    for run in [solve, whole].into_iter().chain(peers) {
        println!("  {:56} {:8.2} us  {:5.2} iterations", run.name, per_problem_us(run), run.iterations);
    }
    for peer in peers {
        println!("ortho9 fit speedup vs {} (CPU time): {:.2}x", peer.name, peer.seconds / solve.seconds);
    }
    println!("ortho9 whole fit / the solve (CPU time): {:.2}x", whole.seconds / solve.seconds);
    for peer in peers {
        println!("ortho9 whole fit speedup vs {} (CPU time): {:.2}x", peer.name, peer.seconds / whole.seconds);
    }
    for peer in peers {
        // Positive: ours is higher (worse); negative: ours is lower.
        let differences = solve.costs.iter().zip(&peer.costs).map(|(ours, theirs)| (ours - theirs) / theirs);
        let worst = differences.fold(f64::NEG_INFINITY, f64::max);
        println!("largest relative cost difference (accelcal - {0}) / {0}: {worst:+.2e}", peer.name);
    }
}

/// The median CPU time of [`REPEATS`] runs of `fit_all` (cost and iterations per problem).
fn median_of(name: &str, mut fit_all: impl FnMut() -> Vec<(f64, usize)>) -> Run {
    let mut seconds = Vec::new();
    let mut results = Vec::new();
    for _ in 0..REPEATS {
        let began = ProcessTime::now();
        results = std::hint::black_box(fit_all());
        seconds.push(began.elapsed().as_secs_f64());
    }
    seconds.sort_by(f64::total_cmp);
    let iterations = results.iter().map(|r| r.1 as f64).sum::<f64>() / results.len() as f64;
    let costs = results.iter().map(|r| r.0).collect();
    Run { name: name.to_owned(), seconds: seconds[REPEATS / 2], iterations, costs }
}

fn per_problem_us(run: &Run) -> f64 {
    run.seconds / PROBLEMS as f64 * 1e6
}

fn tolerance() -> f64 {
    shared::ortho9::step_tolerance::<f64>()
}

/// Runs benches/scipy_ortho9.py on the problems, single-threaded.
fn scipy(readings: &[Vec<[f64; 3]>]) -> Result<Run, String> {
    let input = serde_json::json!({ "problems": readings, "tol": tolerance(), "repeats": REPEATS }).to_string();
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/benches/scipy_ortho9.py");
    let mut python = Command::new("python3");
    python.arg(script);
    let output =
        run_with_input(single_threaded(&mut python), &input).map_err(|e| format!("cannot run python3 ({e})"))?;
    let parsed = serde_json::from_slice::<serde_json::Value>(&output)
        .map_err(|_| "python3 with numpy and scipy is needed (pip install numpy scipy)".to_owned())?;
    let number = |key: &str| parsed[key].as_f64().ok_or(format!("the script printed no {key}"));
    let costs = parsed["costs"].as_array().ok_or("the script printed no costs")?;
    Ok(Run {
        name: "scipy least_squares".to_owned(),
        seconds: number("seconds")?,
        iterations: number("iterations")?,
        costs: costs.iter().filter_map(|c| c.as_f64()).collect(),
    })
}

/// Keeps numerical libraries that could start threads (OpenBLAS, OpenMP) on one.
fn single_threaded(command: &mut Command) -> &mut Command {
    command.env("OMP_NUM_THREADS", "1").env("OPENBLAS_NUM_THREADS", "1").env("MKL_NUM_THREADS", "1")
}

/// Builds benches/ortho9_peers.cc with g++ and runs it on the problems: one run per C++ solver.
fn cpp_peers(readings: &[Vec<[f64; 3]>]) -> Result<Vec<Run>, String> {
    let program = build_cpp_peers()?;
    let mut input = format!("{}\n", readings.len());
    for problem in readings {
        input += &format!("{}\n", problem.len());
        problem.iter().for_each(|m| input += &format!("{:.17e} {:.17e} {:.17e}\n", m[0], m[1], m[2]));
    }
    let mut command = Command::new(&program);
    command.arg(format!("{:.17e}", tolerance())).arg(REPEATS.to_string());
    let output =
        run_with_input(single_threaded(&mut command), &input).map_err(|e| format!("cannot run {program:?} ({e})"))?;
    let text = String::from_utf8_lossy(&output);
    text.lines()
        .map(parse_cpp_line)
        .collect::<Option<Vec<_>>>()
        .filter(|runs| !runs.is_empty())
        .ok_or(format!("unreadable output: {text}"))
}

/// "<name> <seconds> <mean iterations> <cost...>" as a run.
fn parse_cpp_line(line: &str) -> Option<Run> {
    let mut fields = line.split_whitespace();
    let name = fields.next()?.replace('-', " ");
    let seconds = fields.next()?.parse().ok()?;
    let iterations = fields.next()?.parse().ok()?;
    let costs = fields.map(|c| c.parse().unwrap_or(f64::NAN)).collect();
    Some(Run { name, seconds, iterations, costs })
}

/// Compiles the C++ peers once per bench build into cargo's scratch directory.
fn build_cpp_peers() -> Result<PathBuf, String> {
    let source = concat!(env!("CARGO_MANIFEST_DIR"), "/benches/ortho9_peers.cc");
    let program = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("ortho9_peers");
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
