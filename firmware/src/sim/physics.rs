//! What the simulated sensor feels and how it errs: orientation, motion, the true error model, its
//! temperature ([`super::thermal`]), slow bias wander and white noise.

use rand_distr::{Distribution, StandardNormal};
use rand_xoshiro::rand_core::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;
use shared::linalg::{self, Mat3, Vec3};

use super::thermal::{Environment, ThermalDrift};

mod filter;
mod population;
mod power;
mod rotation;
mod wander;

use rotation::{rotate, turning_at};
use wander::Wander;

/// Accelerometer white-noise density of the MPU-6050, in g/sqrt(Hz) (Product Specification 6.2).
pub const ACCEL_NOISE_DENSITY_G: f32 = 400e-6;
/// Gyro rate-noise density of the MPU-6050, in (deg/s)/sqrt(Hz) (Product Specification 6.1); as an
/// angle random walk 0.005 deg/sqrt(s), close to the 0.003 deg/sqrt(s) a user's Allan plot of an
/// MPU-6050 showed (robotics.stackexchange.com question 8860).
pub const GYRO_NOISE_DENSITY_DPS: f32 = 0.005;
/// Accelerometer bias instability, in g: "tens of ug" in Allan plots of consumer MEMS accelerometers
/// of this class (DESIGN.md); 40 ug, as a first-order Markov wander.
pub const ACCEL_BIAS_INSTABILITY_G: f32 = 40e-6;
/// Accelerometer bias random walk, in g/sqrt(s): 1 ug/sqrt(s), 60 ug after an hour, so that over a
/// long thermal run it stays of the order of the bias instability, as the flat Allan curves of such
/// parts over tens of minutes show.
pub const ACCEL_RANDOM_WALK_G: f32 = 1e-6;
/// Gyro bias instability, in deg/s: 0.0012 deg/s (4.3 deg/h), the figure the Allan plot cited at
/// [`GYRO_NOISE_DENSITY_DPS`] gave.
pub const GYRO_BIAS_INSTABILITY_DPS: f32 = 0.0012;
/// Gyro bias random walk, in deg/s/sqrt(s): 2e-5, 1.2e-3 deg/s after an hour, of the order of the
/// bias instability.
pub const GYRO_RANDOM_WALK_DPS: f32 = 2e-5;
/// Correlation time of the bias instability's Markov wander, in seconds.
pub const BIAS_CORRELATION_S: f32 = 100.0;
/// Gyro g-sensitivity, in deg/s per g (Product Specification 6.1, "linear acceleration sensitivity").
pub const GYRO_G_SENSITIVITY_DPS_PER_G: f32 = 0.1;

/// The sensor's true calibration in the convention of `shared::Calibration`: a = M (m - o).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrueErrors {
    /// The true correction matrix M.
    pub matrix: Mat3<f32>,
    /// The true offset o, in g.
    pub offset_g: Vec3<f32>,
    /// The true gyro bias, in deg/s.
    pub gyro_bias_dps: Vec3<f32>,
    /// The true gyro correction G of `w = G (w_raw - b)`: the inverse of the scale and
    /// misalignment the gyro reads the true rate through.
    pub gyro_matrix: Mat3<f32>,
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
            gyro_matrix: linalg::identity(),
        }
    }

    /// A perfect sensor.
    pub fn ideal() -> Self {
        TrueErrors {
            matrix: linalg::identity(),
            offset_g: [0.0; 3],
            gyro_bias_dps: [0.0; 3],
            gyro_matrix: linalg::identity(),
        }
    }

    /// What the uncalibrated sensor reads for a true specific force: m = M^-1 a + o.
    pub fn reading_g(&self, specific_force_g: Vec3<f32>) -> Vec3<f32> {
        let sensor_matrix = linalg::inverse(&self.matrix).unwrap_or(linalg::identity());
        linalg::add(linalg::mul_vec(&sensor_matrix, specific_force_g), self.offset_g)
    }

    /// What the gyro reads for a true rate, before bias and noise: w_raw - b = G^-1 w.
    pub fn gyro_reading_dps(&self, rate_dps: Vec3<f32>) -> Vec3<f32> {
        let sensor_matrix = linalg::inverse(&self.gyro_matrix).unwrap_or(linalg::identity());
        linalg::mul_vec(&sensor_matrix, rate_dps)
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
    /// A hand's turn about a body axis (unit vector) by an angle in degrees over `seconds`: the
    /// rate rises and falls smoothly (a raised cosine, zero at both ends), then the board rests.
    Turning { axis: Vec3<f32>, angle_deg: f32, seconds: f32 },
}

/// The board's state and the sensor's imperfections, evolving with time.
#[derive(Debug, Clone)]
pub struct Physics {
    /// Direction of the specific force in the body frame (unit vector; "up"), at the last set time.
    pub up: Vec3<f32>,
    /// Motion from then on.
    pub motion: Motion,
    /// The true error model at 25 degC.
    pub truth: TrueErrors,
    /// How the errors change with temperature.
    pub drift: ThermalDrift,
    /// The die's temperature and surroundings.
    pub environment: Environment,
    /// Gyro g-sensitivity in deg/s per g, per axis.
    pub gyro_g_sensitivity: f32,
    /// Whether white noise and bias wander are added.
    pub noisy: bool,
    /// Whether the biases wander (instability and random walk).
    pub wandering: bool,
    /// The noise bandwidth of the accelerometer's own filter in Hz (the MPU-6500 family's
    /// ACCEL_CONFIG2); `None`: white noise over the Nyquist band, as the MPU-6050 model has.
    pub accel_bandwidth_hz: Option<f32>,
    accel_filter_state: Option<Vec3<f32>>,
    wander: Wander,
    rng: Xoshiro256PlusPlus,
}

/// One sample in physical units, before quantisation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhysicalSample {
    /// Accelerometer output in g.
    pub accel_g: Vec3<f32>,
    /// Gyro output in deg/s.
    pub gyro_dps: Vec3<f32>,
    /// Temperature TEMP_OUT reports, in degC.
    pub temp_c: f32,
}

impl Physics {
    /// A realistic board with +Z up, just powered on in a 20 degC room: the published error model at
    /// 25 degC, temperature drift, gyro scale, misalignment and g-sensitivity, bias wander and noise,
    /// seeded for repeatability.
    pub fn new(seed: u64) -> Self {
        // NOTE: gyro scale errors within the Product Specification's +-3 % (table 6.1) and
        // misalignments of 0.1-0.35 degrees (a few mrad), typical of the cross-axis sensitivity of
        // +-2 % being mostly package alignment.
        let gyro_sensor_matrix = [[1.021, 0.004, -0.003], [-0.005, 0.984, 0.006], [0.002, -0.004, 1.012]];
        let gyro_matrix = linalg::inverse(&gyro_sensor_matrix).unwrap_or(linalg::identity());
        Physics {
            up: [0.0, 0.0, 1.0],
            motion: Motion::Still,
            truth: TrueErrors { gyro_matrix, ..TrueErrors::published_mpu6050() },
            drift: ThermalDrift::typical(),
            environment: Environment::powered_on_at(20.0),
            gyro_g_sensitivity: GYRO_G_SENSITIVITY_DPS_PER_G,
            noisy: true,
            wandering: true,
            accel_bandwidth_hz: None,
            accel_filter_state: None,
            wander: Wander::stationary(seed),
            rng: Xoshiro256PlusPlus::seed_from_u64(seed),
        }
    }

    /// The published static model held at 25 degC with white noise only: no drift, no wander, an
    /// ideal gyro apart from its bias (for tests of accuracy at one temperature).
    pub fn settled(seed: u64) -> Self {
        Physics {
            drift: ThermalDrift::none(),
            environment: Environment::fixed(super::thermal::TRUTH_REF_TEMP_C),
            truth: TrueErrors::published_mpu6050(),
            gyro_g_sensitivity: 0.0,
            wandering: false,
            wander: Wander::default(),
            ..Physics::new(seed)
        }
    }

    /// The true errors now, at the die's temperature.
    pub fn truth_now(&self) -> TrueErrors {
        self.drift.at(&self.truth, self.environment.die_c)
    }

    /// Lets `seconds` pass without a sample: temperature and bias wander move on.
    pub fn elapse(&mut self, seconds: f32) {
        self.environment.advance(seconds);
        if self.noisy && self.wandering {
            self.wander_step(seconds);
        }
    }

    /// The sample at `seconds` after the orientation was set, for a sensor sampling at `rate_hz`;
    /// one sample period passes first.
    pub fn sample(&mut self, seconds: f32, rate_hz: f32) -> PhysicalSample {
        self.elapse(1.0 / rate_hz);
        let (force, rotation_dps) = self.kinematics(seconds);
        let truth = self.truth_now();
        // NOTE: white noise of density n sampled at f has a standard deviation of n * sqrt(f / 2)
        // (all of it within the Nyquist band), so an average over T seconds has n / sqrt(2 T).
        let band = libm::sqrtf(rate_hz / 2.0);
        let white = match self.accel_bandwidth_hz {
            Some(bandwidth_hz) => self.filtered_accel_noise(bandwidth_hz, 1.0 / rate_hz),
            None => self.noise(ACCEL_NOISE_DENSITY_G * band),
        };
        let accel_noise = linalg::add(white, self.accel_wander());
        let gyro_noise = linalg::add(self.noise(GYRO_NOISE_DENSITY_DPS * band), self.gyro_wander());
        let felt = truth.gyro_reading_dps(rotation_dps);
        let g_effect = linalg::scale(force, self.gyro_g_sensitivity);
        let gyro = linalg::add(linalg::add(felt, truth.gyro_bias_dps), linalg::add(g_effect, gyro_noise));
        PhysicalSample {
            accel_g: linalg::add(truth.reading_g(force), accel_noise),
            gyro_dps: gyro,
            temp_c: self.environment.reading_c(),
        }
    }

    /// The direction up in the body frame `seconds` after the orientation was set (a shake moves
    /// the board about its resting orientation, so only a turn changes it).
    pub fn up_at(&self, seconds: f32) -> Vec3<f32> {
        match self.motion {
            Motion::Rotating { .. } | Motion::Turning { .. } => self.kinematics(seconds).0,
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
            Motion::Turning { axis, angle_deg, seconds: span } => {
                let (angle, rate_dps) = turning_at(angle_deg, span, seconds);
                (rotate(self.up, axis, -angle.to_radians()), linalg::scale(axis, rate_dps))
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
