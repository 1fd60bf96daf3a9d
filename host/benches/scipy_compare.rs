//! ortho9 next to scipy.optimize.least_squares(method='lm') on the same 24-position problems, timed
//! side by side in one run: `cargo bench -p accelcal --bench scipy_compare` (needs python3 with
//! numpy and scipy). Prints the speedup and the largest relative cost difference.

use std::io::Write;
use std::process::{Command, Stdio};
use std::time::Instant;

use accelcal::fit::Model;
use accelcal::fit::{self, FitOptions, ModelChoice};
use accelcal::sim::synthetic::random_positions;

const PROBLEMS: u64 = 200;
const REPEATS: usize = 5;

fn main() {
    let problems: Vec<_> = (0..PROBLEMS).map(|seed| random_positions(1000 + seed, 24, 1e-4, false)).collect();
    let choice = ModelChoice::Only(Model::Ortho9);
    let options = FitOptions::default();

    let mut ours_seconds = f64::INFINITY;
    let mut ours_costs = Vec::new();
    for _ in 0..REPEATS {
        let began = Instant::now();
        let costs: Vec<f64> =
            problems.iter().map(|p| fit::fit(p, choice, &options).map_or(f64::NAN, |f| f.cost)).collect();
        ours_seconds = ours_seconds.min(began.elapsed().as_secs_f64());
        ours_costs = costs;
    }

    let readings: Vec<Vec<[f64; 3]>> = problems.iter().map(|p| p.rows.iter().map(|r| r.reading).collect()).collect();
    let input = serde_json::json!({ "problems": readings }).to_string();
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/benches/scipy_ortho9.py");
    let mut python = match Command::new("python3").arg(script).stdin(Stdio::piped()).stdout(Stdio::piped()).spawn() {
        Ok(child) => child,
        Err(error) => {
            println!("scipy comparison skipped: cannot run python3 ({error})");
            return;
        }
    };
    python.stdin.take().expect("piped").write_all(input.as_bytes()).expect("python reads the problems");
    let output = python.wait_with_output().expect("python runs");
    let Ok(scipy) = serde_json::from_slice::<serde_json::Value>(&output.stdout) else {
        println!("scipy comparison skipped: python3 with numpy and scipy is needed (pip install numpy scipy)");
        return;
    };
    let scipy_seconds = scipy["seconds"].as_f64().expect("seconds");
    let scipy_costs: Vec<f64> = scipy["costs"].as_array().expect("costs").iter().filter_map(|c| c.as_f64()).collect();

    // Positive: ours is higher (worse); negative: ours is lower.
    let worst_relative = ours_costs
        .iter()
        .zip(&scipy_costs)
        .map(|(ours, theirs)| (ours - theirs) / theirs)
        .fold(f64::NEG_INFINITY, f64::max);
    println!(
        "{PROBLEMS} problems, best of {REPEATS}: accelcal {:.2} ms, scipy {:.2} ms",
        ours_seconds * 1e3,
        scipy_seconds * 1e3
    );
    println!("ortho9 fit speedup vs scipy least_squares: {:.1}x", scipy_seconds / ours_seconds);
    println!("largest relative cost difference (accelcal - scipy) / scipy: {worst_relative:+.2e}");
}
