//! The noise analysis of an hour of 1 kHz six-axis data next to allantools' `oadev` on the same data
//! at the same averaging times, thread for thread and by CPU time, in one run:
//! `cargo bench -p accelcal --bench allan_compare` (needs python3 with numpy and allantools).
//! Each side's time is the median of [`REPEATS`] runs over the six axes, on one thread.

use std::process::Command;

use accelcal::noise::{self, allan, RateSeries, TAUS_PER_DECADE};
use accelcal::sim::noise::{noisy_series, TrueNoise};
use cpu_time::ProcessTime;

const RATE_HZ: f64 = 1000.0;
const SAMPLES: usize = 3_600_000;
const REPEATS: usize = 3;

fn main() {
    let truth = TrueNoise { white_noise_density: 400e-6, bias_instability: 0.0, random_walk: 1e-6 };
    let axes: [Vec<f64>; 6] = std::array::from_fn(|k| noisy_series(&truth, k as f64 * 0.1, RATE_HZ, SAMPLES, k as u64));
    let series = RateSeries { rate_hz: RATE_HZ, axes, board: None };
    let factors = allan::averaging_factors(SAMPLES, TAUS_PER_DECADE);
    let deviation = median_cpu_seconds(|| {
        series.axes.iter().for_each(|axis| drop(std::hint::black_box(allan::overlapping_adev(axis, RATE_HZ, &factors))))
    });
    let names = ["ax", "ay", "az", "gx", "gy", "gz"];
    let analysis = median_cpu_seconds(|| {
        let axes = series.axes.iter().zip(names);
        axes.for_each(|(axis, name)| drop(std::hint::black_box(noise::analyse_axis(name, axis, RATE_HZ))))
    });
    let report = noise::analyse(&series);
    let Some((theirs_seconds, adev)) = allantools(&series, &factors) else {
        println!(
            "allantools comparison skipped: python3 with numpy and allantools is needed (pip install allantools numpy)"
        );
        return;
    };
    let worst = report
        .axes
        .iter()
        .zip(adev)
        .flat_map(|(axis, adev)| axis.curve.iter().zip(adev).map(|(p, a)| (p.adev / a - 1.0).abs()).collect::<Vec<_>>())
        .fold(0.0, f64::max);
    println!(
        "an hour at 1 kHz, six axes, {} averaging times each, median of {REPEATS} runs, one thread each:",
        factors.len()
    );
    println!("  accelcal Allan deviation                        {deviation:7.3} s CPU");
    println!("  accelcal noise analysis (deviation, intervals, fit) {analysis:7.3} s CPU");
    println!("  allantools oadev                                {theirs_seconds:7.3} s CPU");
    println!(
        "Allan deviation speedup vs allantools oadev, one thread each (CPU time): {:.1}x",
        theirs_seconds / deviation
    );
    println!(
        "noise analysis speedup vs allantools oadev, one thread each (CPU time): {:.1}x",
        theirs_seconds / analysis
    );
    println!("largest relative difference from allantools: {worst:.2e}");
}

/// The median CPU time of [`REPEATS`] runs of `work`, in seconds.
fn median_cpu_seconds(mut work: impl FnMut()) -> f64 {
    let mut seconds: Vec<f64> = (0..REPEATS)
        .map(|_| {
            let began = ProcessTime::now();
            work();
            began.elapsed().as_secs_f64()
        })
        .collect();
    seconds.sort_by(f64::total_cmp);
    seconds[REPEATS / 2]
}

/// allantools' median CPU seconds and its deviations per axis (benches/allantools_oadev.py).
fn allantools(series: &RateSeries, factors: &[usize]) -> Option<(f64, Vec<Vec<f64>>)> {
    let path = std::env::temp_dir().join(format!("accelcal-allan-bench-{}.f64", std::process::id()));
    let bytes: Vec<u8> = series.axes.iter().flatten().flat_map(|v| v.to_le_bytes()).collect();
    std::fs::write(&path, bytes).ok()?;
    let taus: Vec<f64> = factors.iter().map(|&m| m as f64 / RATE_HZ).collect();
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/benches/allantools_oadev.py");
    let output = Command::new("python3")
        .args([script, &path.display().to_string(), &RATE_HZ.to_string(), &SAMPLES.to_string(), &format!("{taus:?}")])
        .arg(REPEATS.to_string())
        .env("OMP_NUM_THREADS", "1")
        .env("OPENBLAS_NUM_THREADS", "1")
        .env("MKL_NUM_THREADS", "1")
        .output();
    let _ = std::fs::remove_file(&path);
    let theirs = serde_json::from_slice::<serde_json::Value>(&output.ok()?.stdout).ok()?;
    let adev =
        theirs["adev"].as_array()?.iter().map(|a| a.as_array().map(|a| a.iter().filter_map(|v| v.as_f64()).collect()));
    Some((theirs["seconds"].as_f64()?, adev.collect::<Option<Vec<_>>>()?))
}
