//! A person calibrating with their own sketch running: they put the board down, then turn it by
//! hand through 18 orientations in an order of their own (the six faces, the eight corners, four
//! edges, shuffled, each a few degrees off), resting 7.5-9.5 s at each; the realistic simulated sensor
//! (`firmware::sim::physics`) reads it at the sketch's pace. About three minutes in all.

use firmware::sim::physics::{Motion, Physics, TrueErrors};
use rand_xoshiro::rand_core::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;
use shared::linalg::{add, cross, norm, scale};
use shared::orientation::angle_between_deg;

use super::random::{gaussian, random_unit, uniform};

/// How the sketch reads the chip.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reading {
    /// Samples a second the sketch prints.
    pub rate_hz: f64,
    /// Whether the chip's low-pass keeps the noise within the sketch's rate (else the sketch reads
    /// single samples of the 260 Hz-wide signal at its own pace, and the noise aliases in).
    pub filtered: bool,
}

/// One sample as the chip gives it: accelerometer and gyro counts at +-2 g and +-250 deg/s.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ChipSample {
    /// Seconds since the sketch started printing.
    pub at_s: f64,
    /// Accelerometer counts, 16384 a g.
    pub accel: [i16; 3],
    /// Gyro counts, 131 a deg/s.
    pub gyro: [i16; 3],
}

/// A person's session: the samples, and the sensor's true errors at its middle.
#[derive(Debug, Clone)]
pub struct PersonSession {
    /// Every sample the sketch read.
    pub samples: Vec<ChipSample>,
    /// The true errors at the session's middle (its mean temperature).
    pub truth: TrueErrors,
}

/// The chip's full rate with its low-pass open (260 Hz), in Hz.
const CHIP_RATE_HZ: f32 = 1000.0;
/// The board has been on this long before the person starts: a sketch runs a while before anyone
/// calibrates, and the die has mostly warmed.
const WARM_UP_S: f32 = 900.0;
/// Seconds the board rests first, and at each orientation (uniformly between the two).
const FIRST_REST_S: f64 = 5.0;
const REST_S: (f64, f64) = (7.5, 9.5);
/// A person's placement error, in degrees (standard deviation of the angle).
const PLACEMENT_DEG: f64 = 3.0;
/// A turn takes this many seconds plus one per this many degrees (as `SimulatedHand`'s).
const TURN_BASE_S: f64 = 0.6;
const TURN_DPS: f64 = 150.0;

impl PersonSession {
    /// The session of person `seed`, read as `reading`.
    pub fn new(seed: u64, reading: Reading) -> Self {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
        let mut physics = Physics::new(seed);
        physics.elapse(WARM_UP_S);
        let mut clock = SketchClock { physics, reading, at_s: 0.0, samples: Vec::new() };
        clock.rest(FIRST_REST_S);
        let mut up = [0.0, 0.0, 1.0];
        let mut truth = None;
        let order = shuffled(orientations(), &mut rng);
        for (k, wanted) in order.iter().enumerate() {
            let next = placed(*wanted, &mut rng);
            clock.turn(up, next);
            up = next;
            clock.rest(REST_S.0 + (REST_S.1 - REST_S.0) * uniform(&mut rng));
            if k == order.len() / 2 {
                truth = Some(clock.physics.truth_now());
            }
        }
        PersonSession { samples: clock.samples, truth: truth.unwrap_or(TrueErrors::ideal()) }
    }
}

/// The sensor and the sketch's clock.
struct SketchClock {
    physics: Physics,
    reading: Reading,
    at_s: f64,
    samples: Vec<ChipSample>,
}

impl SketchClock {
    fn rest(&mut self, seconds: f64) {
        self.physics.motion = Motion::Still;
        self.run(seconds);
    }

    fn turn(&mut self, from: [f64; 3], to: [f64; 3]) {
        let mut axis = cross(to, from);
        if norm(axis) < 1e-6 {
            axis = cross(from, [0.6, 0.8, 0.0]);
        }
        let angle_deg = angle_between_deg(from, to);
        let seconds = TURN_BASE_S + angle_deg / TURN_DPS;
        let axis = scale(axis, 1.0 / norm(axis)).map(|v| v as f32);
        self.physics.up = from.map(|v| v as f32);
        self.physics.motion = Motion::Turning { axis, angle_deg: angle_deg as f32, seconds: seconds as f32 };
        self.run(seconds);
        self.physics.up = to.map(|v| v as f32);
    }

    /// Samples at the sketch's pace for `seconds` of the current motion.
    fn run(&mut self, seconds: f64) {
        let period = 1.0 / self.reading.rate_hz;
        let (start, end) = (self.at_s, self.at_s + seconds);
        while self.at_s < end {
            let rate = if self.reading.filtered { self.reading.rate_hz as f32 } else { CHIP_RATE_HZ };
            self.physics.elapse((period - 1.0 / f64::from(rate)).max(0.0) as f32);
            let sample = self.physics.sample((self.at_s - start) as f32, rate);
            let counts = |v: [f32; 3], per: f32| v.map(|x| (x * per).round().clamp(-32768.0, 32767.0) as i16);
            let (accel, gyro) = (counts(sample.accel_g, 16384.0), counts(sample.gyro_dps, 131.0));
            self.samples.push(ChipSample { at_s: self.at_s, accel, gyro });
            self.at_s += period;
        }
    }
}

/// The 18 orientations: faces, corners and four edges around the middle.
fn orientations() -> Vec<[f64; 3]> {
    let faces = (0..6).map(|k| {
        let mut up = [0.0; 3];
        up[k % 3] = if k < 3 { 1.0 } else { -1.0 };
        up
    });
    let corners = (0..8).map(|k| [k & 1, k & 2, k & 4].map(|b| if b == 0 { 1.0 } else { -1.0 }));
    let edges = [[1.0, 1.0, 0.0], [1.0, -1.0, 0.0], [-1.0, 1.0, 0.0], [-1.0, -1.0, 0.0]].into_iter();
    faces.chain(corners).chain(edges).map(|v| scale(v, 1.0 / norm(v))).collect()
}

fn shuffled(mut items: Vec<[f64; 3]>, rng: &mut Xoshiro256PlusPlus) -> Vec<[f64; 3]> {
    for i in (1..items.len()).rev() {
        let pick = ((i + 1) as f64 * uniform(rng)) as usize;
        items.swap(i, pick.min(i));
    }
    items
}

/// `up` a few degrees off, as a hand puts it down.
fn placed(up: [f64; 3], rng: &mut Xoshiro256PlusPlus) -> [f64; 3] {
    let off = PLACEMENT_DEG.to_radians() * gaussian(rng);
    let moved = add(up, scale(random_unit(rng), off));
    scale(moved, 1.0 / norm(moved))
}
