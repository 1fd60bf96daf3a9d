//! A simulated hand that keeps turning (issue 38): rests joined by smooth turns about a fixed body
//! axis, during each turn a linear acceleration whose velocity and displacement vanish at both
//! rests, and the sensor's errors, white noise and each group's low-pass delay applied to every
//! sample of both groups.
//!
//! The turn: the angle rises as theta(t) = A (t/D - sin(2 pi t/D) / (2 pi)), so the rate is
//! A/D (1 - cos(2 pi t/D)), zero with its slope at both ends. The hand's acceleration, per world axis,
//! is sum_k c_k cos(2 pi k t/D) over k = 1..3 with sum c_k = 0: zero at both ends, and its velocity
//! (sin terms) and displacement (1 - cos terms) are zero at t = 0 and t = D.

use std::f64::consts::TAU;

use firmware::sim::physics::{TrueErrors, ACCEL_NOISE_DENSITY_G, GYRO_G_SENSITIVITY_DPS_PER_G, GYRO_NOISE_DENSITY_DPS};
use nalgebra::{Matrix3, Rotation3, Unit, Vector3};
use rand_xoshiro::rand_core::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

use super::random::{gaussian, random_unit, uniform};
use crate::fit::motion::{world_up, JointModel, MotionData, Orientation, SensorNoise};

/// The accelerometer's group delay at DLPF_CFG = 1, in seconds (Register Map RM-MPU-6000A rev 4.2,
/// register 26: 184 Hz, 2.0 ms).
pub const ACCEL_DELAY_S: f64 = 2.0e-3;
/// The gyro's group delay at DLPF_CFG = 1, in seconds (same table: 188 Hz, 1.9 ms).
pub const GYRO_DELAY_S: f64 = 1.9e-3;
/// The gyro's sensitivity tolerance as one standard deviation (Product Specification 6.1: +-3 %).
const GYRO_SCALE_SPREAD: f64 = 0.015;
/// The gyro's cross-axis sensitivity as one standard deviation (Product Specification 6.1: +-2 %).
const GYRO_CROSS_SPREAD: f64 = 0.01;
/// Full scale of the +-2 g range and of the +-1000 deg/s range the stream uses.
const ACCEL_FULL_SCALE_G: f64 = 2.0;
const GYRO_FULL_SCALE_DPS: f64 = 1000.0;

/// The shape of a keep-turning session.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MotionPlan {
    /// Samples per second, in Hz.
    pub rate_hz: f64,
    /// Rests, each followed by a turn but the last.
    pub rests: usize,
    /// Length of each rest, in seconds.
    pub rest_s: f64,
    /// Length of each turn, in seconds.
    pub turn_s: f64,
    /// The hand's linear acceleration, rms of its magnitude over a turn, in g.
    pub linear_rms_g: f64,
    /// Whether white noise is added.
    pub noisy: bool,
    /// Whether the rests are designed (the body's up at the twelve vertices of an icosahedron, each
    /// turn carrying it to the next about the line perpendicular to both), else each turn is about a
    /// random axis by 90 to 180 degrees.
    pub spread: bool,
}

impl MotionPlan {
    /// A one-minute session at a person's pace: twelve rests of 2.1 s, eleven turns of 3 s, 1 kHz,
    /// a hand of 0.15 g rms (issue 38's design: 25 s of rest).
    pub fn one_minute() -> Self {
        MotionPlan {
            rate_hz: 1000.0,
            rests: 12,
            rest_s: 2.1,
            turn_s: 3.0,
            linear_rms_g: 0.15,
            noisy: true,
            spread: true,
        }
    }
}

/// One turn as the hand makes it.
#[derive(Debug, Clone, Copy, PartialEq)]
struct HandTurn {
    /// When it starts, in seconds.
    start_s: f64,
    /// The body axis it turns about.
    axis: Unit<Vector3<f64>>,
    /// How far, in radians.
    angle_rad: f64,
    /// The world linear acceleration's cosine amplitudes (k = 1, 2, 3), in g.
    amplitudes_g: [Vector3<f64>; 3],
}

/// A simulated session: the data as the fit reads it and the truth behind it.
#[derive(Debug, Clone)]
pub struct MotionSession {
    /// What the board streamed.
    pub data: MotionData,
    /// The true sensor model (its skew the gyro's delay less the accelerometer's).
    pub truth: JointModel,
    /// Each rest's true orientation, body to world.
    pub orientations: Vec<Orientation>,
}

/// The true errors of the simulated part: the published MPU-6050's accelerometer, a gyro drawn
/// from the datasheet's tolerances about the identity, its published g-sensitivity on each axis.
pub fn true_model(rng: &mut Xoshiro256PlusPlus) -> JointModel {
    let published = TrueErrors::published_mpu6050();
    let m = Matrix3::from_fn(|i, j| f64::from(published.matrix[i][j]));
    let cross = Matrix3::from_fn(|i, j| if i == j { 0.0 } else { GYRO_CROSS_SPREAD * gaussian(rng) });
    let scale = Matrix3::from_diagonal(&Vector3::from_fn(|_, _| 1.0 + GYRO_SCALE_SPREAD * gaussian(rng)));
    JointModel {
        accel_matrix: m,
        accel_offset_g: Vector3::from(published.offset_g.map(f64::from)),
        gyro_matrix: scale + cross,
        gyro_bias_dps: Vector3::from(published.gyro_bias_dps.map(f64::from)),
        g_sensitivity_dps_per_g: Matrix3::identity() * f64::from(GYRO_G_SENSITIVITY_DPS_PER_G),
        skew_s: GYRO_DELAY_S - ACCEL_DELAY_S,
    }
}

/// The datasheet's white noise (the firmware simulation's figures).
pub fn datasheet_noise() -> SensorNoise {
    SensorNoise {
        accel_density_g: f64::from(ACCEL_NOISE_DENSITY_G),
        gyro_density_dps: f64::from(GYRO_NOISE_DENSITY_DPS),
    }
}

/// A session of `plan` drawn by `seed`: the part's errors, the turns and the noise.
pub fn simulate(plan: &MotionPlan, seed: u64) -> MotionSession {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let truth = true_model(&mut rng);
    let heading = Rotation3::from_axis_angle(&Vector3::z_axis(), TAU * uniform(&mut rng));
    let first = match plan.spread {
        true => heading * Rotation3::rotation_between(&spread_up(0), &world_up()).unwrap_or_else(Rotation3::identity),
        false => Rotation3::new(Vector3::from(random_unit(&mut rng)) * (TAU * uniform(&mut rng))),
    };
    let turns: Vec<HandTurn> = (0..plan.rests - 1).map(|k| hand_turn(plan, k, &mut rng)).collect();
    let orientations = rest_orientations(first, &turns);
    let samples = ((plan.rests as f64 * plan.rest_s + turns.len() as f64 * plan.turn_s) * plan.rate_hz) as usize;
    let hand = Hand { plan, turns: &turns, orientations: &orientations };
    let (mut accel_g, mut gyro_dps) = (Vec::with_capacity(samples), Vec::with_capacity(samples));
    let [accel_sigma, gyro_sigma] = [ACCEL_NOISE_DENSITY_G, GYRO_NOISE_DENSITY_DPS].map(|density| {
        if plan.noisy {
            f64::from(density) * (plan.rate_hz / 2.0).sqrt()
        } else {
            0.0
        }
    });
    for i in 0..samples {
        let t = i as f64 / plan.rate_hz;
        let (force, _) = hand.at(t - ACCEL_DELAY_S);
        let (force_late, rate) = hand.at(t - GYRO_DELAY_S);
        accel_g.push(reading_g(&truth, &force) + noise(&mut rng, accel_sigma));
        gyro_dps.push(gyro_reading_dps(&truth, &rate, &force_late) + noise(&mut rng, gyro_sigma));
    }
    let data = MotionData {
        rate_hz: plan.rate_hz,
        accel_g,
        gyro_dps,
        indices: (0..samples as u64).collect(),
        rests: rest_ranges(plan),
        accel_full_scale_g: ACCEL_FULL_SCALE_G,
        gyro_full_scale_dps: GYRO_FULL_SCALE_DPS,
        noise: datasheet_noise(),
    };
    MotionSession { data, truth, orientations }
}

/// Turn `k`: a random body axis, 90 to 180 degrees, and a hand's acceleration of the plan's rms.
fn hand_turn(plan: &MotionPlan, k: usize, rng: &mut Xoshiro256PlusPlus) -> HandTurn {
    let (before, after) = (spread_up(k), spread_up(k + 1));
    // NOTE: turning the body by q about a body axis turns its up by q^-1: about after x before.
    let (axis, angle_rad) = match Unit::try_new(after.cross(&before), 1e-6).filter(|_| plan.spread) {
        Some(axis) => (axis, before.angle(&after)),
        None => (Unit::new_normalize(Vector3::from(random_unit(rng))), (90.0 + 90.0 * uniform(rng)).to_radians()),
    };
    let [a, b] = [(); 2].map(|()| Vector3::from_fn(|_, _| gaussian(rng)));
    // NOTE: c1 = a, c2 = b - a, c3 = -b sum to zero; the mean square of sum c_k cos(k w t) is
    // sum |c_k|^2 / 2.
    let amplitudes = [a, b - a, -b];
    let mean_square: f64 = amplitudes.iter().map(|c| c.norm_squared() / 2.0).sum();
    let amplitudes_g = amplitudes.map(|c| c * (plan.linear_rms_g / mean_square.sqrt()));
    HandTurn { start_s: (k + 1) as f64 * plan.rest_s + k as f64 * plan.turn_s, axis, angle_rad, amplitudes_g }
}

/// The body's up at designed rest `k`: the icosahedron's vertices (0, +-1, +-phi) and their cyclic
/// shifts, in an order whose successive vertices are 116.6 degrees apart (the last pair 63.4), so
/// every turn is a large one and no two rests repeat.
fn spread_up(k: usize) -> Vector3<f64> {
    const ORDER: [usize; 12] = [0, 3, 2, 5, 1, 4, 11, 6, 7, 8, 10, 9];
    let phi = (1.0 + 5f64.sqrt()) / 2.0;
    let i = ORDER[k % 12];
    let (a, b) = (if i < 6 { 1.0 } else { -1.0 }, if (i / 3).is_multiple_of(2) { phi } else { -phi });
    let v = [Vector3::new(0.0, a, b), Vector3::new(a, b, 0.0), Vector3::new(b, 0.0, a)][i % 3];
    v.normalize()
}

/// Each rest's orientation: the first, then each turned by the turn before it.
fn rest_orientations(first: Orientation, turns: &[HandTurn]) -> Vec<Orientation> {
    let mut orientations = vec![first];
    for turn in turns {
        let last = orientations[orientations.len() - 1];
        orientations.push(last * Rotation3::from_axis_angle(&turn.axis, turn.angle_rad));
    }
    orientations
}

/// The sample ranges of the rests, 50 ms in from each end (the filter's delay and margin).
fn rest_ranges(plan: &MotionPlan) -> Vec<std::ops::Range<usize>> {
    let margin_s = 0.05;
    let index = |t: f64| (t * plan.rate_hz).round() as usize;
    (0..plan.rests)
        .map(|k| {
            let start = k as f64 * (plan.rest_s + plan.turn_s);
            index(start + margin_s)..index(start + plan.rest_s - margin_s)
        })
        .collect()
}

/// The hand's whole session, evaluated at any time.
struct Hand<'a> {
    plan: &'a MotionPlan,
    turns: &'a [HandTurn],
    orientations: &'a [Orientation],
}

impl Hand<'_> {
    /// The true specific force in the body, in g, and the true body rate, in rad/s, at `t` seconds.
    fn at(&self, t: f64) -> (Vector3<f64>, Vector3<f64>) {
        let period = self.plan.rest_s + self.plan.turn_s;
        let k = ((t / period).floor().max(0.0) as usize).min(self.orientations.len() - 1);
        let since = t - self.turns.get(k).map_or(f64::INFINITY, |turn| turn.start_s);
        match self.turns.get(k).filter(|_| (0.0..self.plan.turn_s).contains(&since)) {
            Some(turn) => self.turning(turn, &self.orientations[k], since),
            None => (self.orientations[k].inverse() * world_up(), Vector3::zeros()),
        }
    }

    /// Within `turn`, `since` seconds after it began from `start`.
    fn turning(&self, turn: &HandTurn, start: &Orientation, since: f64) -> (Vector3<f64>, Vector3<f64>) {
        let d = self.plan.turn_s;
        let phase = TAU * since / d;
        let angle = turn.angle_rad * (since / d - phase.sin() / TAU);
        let rate = turn.axis.into_inner() * (turn.angle_rad / d * (1.0 - phase.cos()));
        let rotation = start * Rotation3::from_axis_angle(&turn.axis, angle);
        let linear: Vector3<f64> = (0..3).map(|k| turn.amplitudes_g[k] * ((k + 1) as f64 * phase).cos()).sum();
        (rotation.inverse() * (world_up() + linear), rate)
    }
}

/// What the accelerometer reads for a true specific force: m = M^-1 f + o.
fn reading_g(truth: &JointModel, force: &Vector3<f64>) -> Vector3<f64> {
    truth.accel_matrix.try_inverse().unwrap_or_else(Matrix3::identity) * force + truth.accel_offset_g
}

/// What the gyro reads for a true rate in rad/s: w_raw = G^-1 w + b + S f, in deg/s.
fn gyro_reading_dps(truth: &JointModel, rate: &Vector3<f64>, force: &Vector3<f64>) -> Vector3<f64> {
    let felt = truth.gyro_matrix.try_inverse().unwrap_or_else(Matrix3::identity) * rate.map(f64::to_degrees);
    felt + truth.gyro_bias_dps + truth.g_sensitivity_dps_per_g * force
}

/// White noise of `sigma` per axis.
fn noise(rng: &mut Xoshiro256PlusPlus, sigma: f64) -> Vector3<f64> {
    Vector3::from_fn(|_, _| sigma * gaussian(rng))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_designed_session_rests_with_its_up_at_each_vertex_of_an_icosahedron() {
        let plan = MotionPlan { rate_hz: 100.0, noisy: false, ..MotionPlan::one_minute() };
        let session = simulate(&plan, 7);
        let ups: Vec<Vector3<f64>> = session.orientations.iter().map(|r| r.inverse() * world_up()).collect();
        for (k, up) in ups.iter().enumerate() {
            assert!((up - spread_up(k)).norm() < 1e-9, "rest {k}: up {up:?}, designed {:?}", spread_up(k));
            // Twelve distinct vertices: the nearest other rest is an icosahedron's edge away, 63.4 degrees.
            let nearest = ups.iter().enumerate().filter(|&(j, _)| j != k).map(|(_, v)| up.angle(v).to_degrees());
            assert!((nearest.fold(180.0, f64::min) - 63.43).abs() < 0.01, "rest {k} repeats another");
        }
    }
}
