//! The joint fit of a simulated one-minute session at 1 kHz (issue 38: at most 1 s of CPU):
//! `cargo bench -p accelcal-core --features sim --bench motion`. The time is the median of
//! [`REPEATS`] fits of the same session, by the process's CPU time, as the host's benches measure.

use accelcal_core::fit::motion::fit_joint;
use accelcal_core::sim::motion::{simulate, MotionPlan};
use cpu_time::ProcessTime;

const REPEATS: usize = 7;

fn main() {
    let session = simulate(&MotionPlan::one_minute(), 1);
    let samples = session.data.accel_g.len();
    let mut seconds: Vec<f64> = (0..REPEATS)
        .map(|_| {
            let began = ProcessTime::now();
            let fit = fit_joint(std::hint::black_box(&session.data));
            let elapsed = began.elapsed().as_secs_f64();
            assert!(fit.is_some(), "the joint fit converges");
            elapsed
        })
        .collect();
    seconds.sort_by(f64::total_cmp);
    println!(
        "joint fit of a one-minute session ({samples} samples at 1 kHz): median {:.4} s CPU of {REPEATS} (fastest {:.4} s, slowest {:.4} s)",
        seconds[REPEATS / 2],
        seconds[0],
        seconds[REPEATS - 1]
    );
}
