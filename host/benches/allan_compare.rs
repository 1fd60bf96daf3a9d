//! The noise analysis of an hour of 1 kHz six-axis data next to allantools' `oadev` on the same data
//! at the same averaging times, timed side by side in one run:
//! `cargo bench -p accelcal --bench allan_compare` (needs python3 with numpy and allantools).
//! Prints `adev speedup vs allantools: N.Nx` and the largest relative difference.

use std::process::Command;
use std::time::Instant;

use accelcal::noise::{self, allan, RateSeries, TAUS_PER_DECADE};
use accelcal::sim::noise::{noisy_series, TrueNoise};

const RATE_HZ: f64 = 1000.0;
const SAMPLES: usize = 3_600_000;

fn main() {
    let truth = TrueNoise { white_noise_density: 400e-6, bias_instability: 0.0, random_walk: 1e-6 };
    let axes: [Vec<f64>; 6] = std::array::from_fn(|k| noisy_series(&truth, k as f64 * 0.1, RATE_HZ, SAMPLES, k as u64));
    let series = RateSeries { rate_hz: RATE_HZ, axes };

    let began = Instant::now();
    let report = noise::analyse(&series);
    let ours_all = began.elapsed().as_secs_f64();
    let factors = allan::averaging_factors(SAMPLES, TAUS_PER_DECADE);
    let began = Instant::now();
    for axis in &series.axes {
        std::hint::black_box(allan::overlapping_adev(axis, RATE_HZ, &factors));
    }
    let ours_one_thread = began.elapsed().as_secs_f64();

    let path = std::env::temp_dir().join(format!("accelcal-allan-bench-{}.f64", std::process::id()));
    let bytes: Vec<u8> = series.axes.iter().flatten().flat_map(|v| v.to_le_bytes()).collect();
    std::fs::write(&path, bytes).expect("temporary file written");
    let taus: Vec<f64> = factors.iter().map(|&m| m as f64 / RATE_HZ).collect();
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/benches/allantools_oadev.py");
    let output = Command::new("python3")
        .args([script, &path.display().to_string(), &RATE_HZ.to_string(), &SAMPLES.to_string(), &format!("{taus:?}")])
        .output();
    let _ = std::fs::remove_file(&path);
    let theirs = match output.ok().and_then(|o| serde_json::from_slice::<serde_json::Value>(&o.stdout).ok()) {
        Some(theirs) => theirs,
        None => {
            println!("allantools comparison skipped: python3 with numpy and allantools is needed (pip install allantools numpy)");
            return;
        }
    };
    let theirs_seconds = theirs["seconds"].as_f64().expect("seconds");
    let worst = report
        .axes
        .iter()
        .zip(theirs["adev"].as_array().expect("adev"))
        .flat_map(|(axis, adev)| {
            let adev: Vec<f64> = adev.as_array().expect("list").iter().filter_map(|v| v.as_f64()).collect();
            axis.curve.iter().zip(adev).map(|(p, a)| (p.adev / a - 1.0).abs()).collect::<Vec<_>>()
        })
        .fold(0.0, f64::max);
    println!("an hour at 1 kHz, six axes, {} averaging times each:", factors.len());
    println!(
        "accelcal: {:.3} s (deviation, intervals and fit, one thread per axis); {:.3} s (deviation only, one thread); allantools oadev: {:.3} s",
        ours_all, ours_one_thread, theirs_seconds
    );
    println!("adev speedup vs allantools: {:.1}x", theirs_seconds / ours_all);
    println!("adev speedup vs allantools, one thread, deviation only: {:.1}x", theirs_seconds / ours_one_thread);
    println!("largest relative difference from allantools: {worst:.2e}");
}
