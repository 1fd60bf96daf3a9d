//! What the simulated sensor feels and how it errs: orientation, motion, the true error model, noise.

use rand_distr::{Distribution, StandardNormal};
use rand_xoshiro::rand_core::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;
use shared::linalg::{self, Mat3, Vec3};

/// Accelerometer white-noise density of the MPU-6050, in g/sqrt(Hz) (Product Specification 6.2).
pub const ACCEL_NOISE_DENSITY_G: f32 = 400e-6;
/// Gyro rate-noise density of the MPU-6050, in (deg/s)/sqrt(Hz) (Product Specification 6.1).
pub const GYRO_NOISE_DENSITY_DPS: f32 = 0.005;

/// The sensor's true calibration in the convention of `shared::Calibration`: a = M (m - o).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrueErrors {
    /// The true correction matrix M.
    pub matrix: Mat3<f32>,
    /// The true offset o, in g.
    pub offset_g: Vec3<f32>,
    /// The true gyro bias, in deg/s.
    pub gyro_bias_dps: Vec3<f32>,
}

impl TrueErrors {
    /// The published MPU-6050 estimates (Marinov and Petrov 2019, Table 1): M = T K, o = b.
    pub fn published_mpu6050() -> Self {
        let (a_yz, a_zy, a_zx) = (3.58e-4, -7.29e-3, 4.62e-4);
        let (s_x, s_y, s_z) = (1.0006, 1.0030, 0.9834);
        let t = [[1.0, a_yz, a_zy], [0.0, 1.0, a_zx], [0.0, 0.0, 1.0]];
        let k = [[s_x, 0.0, 0.0], [0.0, s_y, 0.0], [0.0, 0.0, s_z]];
        TrueErrors {
            matrix: linalg::mul_mat(&t, &k),
            offset_g: [27.6253e-3, -5.7079e-3, -78.2870e-3],
            // NOTE: no gyro figures were published; a bias of about a degree per second is typical
            // of the datasheet's +-20 deg/s initial tolerance on good parts.
            gyro_bias_dps: [-1.2, 0.8, 0.35],
        }
    }

    /// A perfect sensor.
    pub fn ideal() -> Self {
        TrueErrors { matrix: linalg::identity(), offset_g: [0.0; 3], gyro_bias_dps: [0.0; 3] }
    }

    /// What the uncalibrated sensor reads for a true specific force: m = M^-1 a + o.
    pub fn reading_g(&self, specific_force_g: Vec3<f32>) -> Vec3<f32> {
        let sensor_matrix = linalg::inverse(&self.matrix).unwrap_or(linalg::identity());
        linalg::add(linalg::mul_vec(&sensor_matrix, specific_force_g), self.offset_g)
    }
}

/// How the simulated board moves.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Motion {
    /// Resting.
    Still,
    /// Turning steadily about a body axis (unit vector) at a rate in deg/s.
    Rotating { axis: Vec3<f32>, rate_dps: f32 },
    /// Shaken sinusoidally along body x with an amplitude in g, as a hand's tremor.
    Vibrating { amplitude_g: f32, frequency_hz: f32 },
}

/// The board's state and the sensor's imperfections, evolving with time.
#[derive(Debug, Clone)]
pub struct Physics {
    /// Direction of the specific force in the body frame (unit vector; "up"), at the last set time.
    pub up: Vec3<f32>,
    /// Motion from then on.
    pub motion: Motion,
    /// The true error model.
    pub truth: TrueErrors,
    /// Die temperature in degC.
    pub temp_c: f32,
    /// Whether white noise is added.
    pub noisy: bool,
    rng: Xoshiro256PlusPlus,
}

/// One sample in physical units, before quantisation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhysicalSample {
    /// Accelerometer output in g.
    pub accel_g: Vec3<f32>,
    /// Gyro output in deg/s.
    pub gyro_dps: Vec3<f32>,
    /// Temperature in degC.
    pub temp_c: f32,
}

impl Physics {
    /// A still board with +Z up, the published error model and noise, seeded for repeatability.
    pub fn new(seed: u64) -> Self {
        Physics {
            up: [0.0, 0.0, 1.0],
            motion: Motion::Still,
            truth: TrueErrors::published_mpu6050(),
            temp_c: 25.0,
            noisy: true,
            rng: Xoshiro256PlusPlus::seed_from_u64(seed),
        }
    }

    /// The sample at `seconds` after the orientation was set, for a sensor sampling at `rate_hz`.
    pub fn sample(&mut self, seconds: f32, rate_hz: f32) -> PhysicalSample {
        let (force, rotation_dps) = self.kinematics(seconds);
        // NOTE: white noise of density n sampled at f has a standard deviation of n * sqrt(f / 2)
        // (all of it within the Nyquist band), so an average over T seconds has n / sqrt(2 T).
        let band = libm::sqrtf(rate_hz / 2.0);
        let accel_noise = self.noise(ACCEL_NOISE_DENSITY_G * band);
        let gyro_noise = self.noise(GYRO_NOISE_DENSITY_DPS * band);
        let gyro = linalg::add(linalg::add(rotation_dps, self.truth.gyro_bias_dps), gyro_noise);
        PhysicalSample {
            accel_g: linalg::add(self.truth.reading_g(force), accel_noise),
            gyro_dps: gyro,
            temp_c: self.temp_c,
        }
    }

    /// The direction up in the body frame `seconds` after the orientation was set (a shake moves
    /// the board about its resting orientation, so only a turn changes it).
    pub fn up_at(&self, seconds: f32) -> Vec3<f32> {
        match self.motion {
            Motion::Rotating { .. } => self.kinematics(seconds).0,
            Motion::Still | Motion::Vibrating { .. } => self.up,
        }
    }

    /// True specific force (g) and angular rate (deg/s) at a time.
    fn kinematics(&self, seconds: f32) -> (Vec3<f32>, Vec3<f32>) {
        match self.motion {
            Motion::Still => (self.up, [0.0; 3]),
            Motion::Rotating { axis, rate_dps } => {
                // The board turns by +angle, so gravity turns by -angle in the body frame.
                let angle = -(rate_dps * seconds).to_radians();
                (rotate(self.up, axis, angle), linalg::scale(axis, rate_dps))
            }
            Motion::Vibrating { amplitude_g, frequency_hz } => {
                let shake = amplitude_g * libm::sinf(2.0 * core::f32::consts::PI * frequency_hz * seconds);
                (linalg::add(self.up, [shake, 0.0, 0.0]), [0.0; 3])
            }
        }
    }

    fn noise(&mut self, sigma: f32) -> Vec3<f32> {
        if !self.noisy {
            return [0.0; 3];
        }
        let mut draw = || sigma * <StandardNormal as Distribution<f32>>::sample(&StandardNormal, &mut self.rng);
        [draw(), draw(), draw()]
    }
}

/// Rodrigues' rotation of v about a unit axis by an angle in radians.
fn rotate(v: Vec3<f32>, axis: Vec3<f32>, angle: f32) -> Vec3<f32> {
    let (sin, cos) = (libm::sinf(angle), libm::cosf(angle));
    let along = linalg::scale(axis, linalg::dot(axis, v) * (1.0 - cos));
    linalg::add(linalg::add(linalg::scale(v, cos), linalg::scale(linalg::cross(axis, v), sin)), along)
}
