//! Simulated sessions made up for tests: a sensor of known errors, its captures drawn with noise.

use rand_xoshiro::rand_core::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

use super::random::gaussian;
use crate::orientation::{corners, faces, Orientation};
use crate::run::drift::{closing, order};
use crate::session::{CaptureRecord, Session, SessionKind};

/// A capture of a sensor with M^-1 = a triangular sensor matrix and offset o(T) = o + c (T - 22), at
/// `up` and `temp_c`, its mean off by `error_g`, stating `std_g` over `samples`.
fn capture(target: &Orientation, temp_c: f64, error_g: [f64; 3], std_g: f32) -> CaptureRecord {
    let sensor = [[1.01, 0.002, -0.004], [0.0, 0.99, 0.003], [0.0, 0.0, 1.02]];
    let offset = [0.03, -0.01, -0.08];
    let slope = [0.75e-3, -0.7e-3, 1.4e-3];
    let mean = [0, 1, 2].map(|i| {
        let felt: f64 = (0..3).map(|j| sensor[i][j] * target.up[j]).sum();
        felt + offset[i] + slope[i] * (temp_c - 22.0) + error_g[i]
    });
    CaptureRecord::still(target, mean, std_g, 400, temp_c)
}

/// An adaptive session of the fifteen captures, warming `warming_c` over it, each mean off by its
/// noise (`std_g` / sqrt(400)) drawn from `seed`.
pub fn adaptive(seed: u64, warming_c: f64, std_g: f32) -> Session {
    let mut targets = order(&[faces(), corners()].concat());
    targets.push(closing(&targets[0]));
    let mut random = Xoshiro256PlusPlus::seed_from_u64(seed);
    let sigma = f64::from(std_g) / 20.0;
    let captures = targets.iter().enumerate().map(|(i, t)| {
        let error = [0; 3].map(|_| gaussian(&mut random) * sigma);
        capture(t, 21.5 + warming_c * i as f64 / 14.0, error, std_g)
    });
    let mut captures: Vec<CaptureRecord> = captures.collect();
    captures.last_mut().unwrap().closing = true;
    Session { kind: SessionKind::Adaptive, captures, ..Session::default() }
}
