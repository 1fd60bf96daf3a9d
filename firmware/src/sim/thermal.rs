//! The simulated sensor's temperature and everything that follows it: the die warming after
//! power-on and following its surroundings, and the accelerometer offset and sensitivity and the gyro
//! bias moving with it. The drift follows DESIGN.md's temperature convention exactly (powers of
//! T - 25 degC), so the published static model is the truth at 25 degC.

use shared::linalg::{self, Vec3};

use super::physics::TrueErrors;

/// The die temperature at which the static truth (Marinov and Petrov) holds, in degC.
pub const TRUTH_REF_TEMP_C: f32 = 25.0;

/// How the die temperature evolves: a first-order lag towards the surroundings plus self-heating.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Environment {
    /// Temperature of the surroundings now, in degC.
    pub ambient_c: f32,
    /// Where a ramp of the surroundings stops, in degC.
    pub ramp_target_c: f32,
    /// How fast the surroundings move towards `ramp_target_c`, in degC/s (0: they stay).
    pub ramp_c_per_s: f32,
    /// How far above its surroundings the powered die settles, in degC.
    pub self_heating_c: f32,
    /// Time constant of the die following its surroundings and its own heat, in seconds.
    pub time_constant_s: f32,
    /// What TEMP_OUT reads above the true die temperature, in degC (the sensor is untrimmed).
    pub reading_offset_c: f32,
    /// The true die temperature now, in degC.
    pub die_c: f32,
}

impl Environment {
    /// A board powered on in a 20 degC room: the die starts at room temperature and settles at the
    /// static truth's 25 degC.
    // NOTE: self-heating. InvenSense does not specify it; flight-controller users report the IMU
    // warming by 4-8 degC within the first five to ten minutes after power-on (which is why
    // ArduPilot and PX4 learn their temperature models during warm-up). 5 degC with a 4-minute time
    // constant sits in that band.
    // NOTE: untrimmed offset. The register map gives TEMP_OUT = raw / 340 + 36.53 and calls the
    // sensor untrimmed: parts differ from the formula by a few degC; +1.5 degC is one such part.
    pub const fn powered_on_at(ambient_c: f32) -> Self {
        Environment {
            ambient_c,
            ramp_target_c: ambient_c,
            ramp_c_per_s: 0.0,
            self_heating_c: 5.0,
            time_constant_s: 240.0,
            reading_offset_c: 1.5,
            die_c: ambient_c,
        }
    }

    /// A die held at `die_c` for good: no self-heating, no lag, no reading offset (for tests that
    /// need one temperature only).
    pub const fn fixed(die_c: f32) -> Self {
        Environment {
            ambient_c: die_c,
            ramp_target_c: die_c,
            ramp_c_per_s: 0.0,
            self_heating_c: 0.0,
            time_constant_s: 1.0,
            reading_offset_c: 0.0,
            die_c,
        }
    }

    /// Moves the surroundings towards `target_c` at `c_per_s` degC/s (infinite: a step).
    pub fn ramp_to(&mut self, target_c: f32, c_per_s: f32) {
        self.ramp_target_c = target_c;
        self.ramp_c_per_s = c_per_s.abs();
    }

    /// The temperature the sensor reports, in degC.
    pub fn reading_c(&self) -> f32 {
        self.die_c + self.reading_offset_c
    }

    /// Lets `seconds` pass: the surroundings ramp, the die follows.
    pub fn advance(&mut self, seconds: f32) {
        if seconds <= 0.0 {
            return;
        }
        let step = self.ramp_c_per_s * seconds;
        let gap = self.ramp_target_c - self.ambient_c;
        self.ambient_c += gap.clamp(-step, step);
        let settled = self.ambient_c + self.self_heating_c;
        // NOTE: exact for a constant target; the target moves slowly compared with the steps used.
        let follow = 1.0 - libm::expf(-seconds / self.time_constant_s);
        self.die_c += (settled - self.die_c) * follow;
    }
}

/// How the sensor's errors change with the die temperature: coefficients of (T - 25 degC) and its
/// square, per axis, in DESIGN.md's convention.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ThermalDrift {
    /// Accelerometer offset drift c1, c2 in g/degC, g/degC^2: o(T) = o + c1 dT + c2 dT^2.
    pub offset_g: [Vec3<f32>; 2],
    /// Sensitivity drift d1, d2 in 1/degC, 1/degC^2: the sensor reads (1 + d1 dT + d2 dT^2) times more.
    pub scale: [Vec3<f32>; 2],
    /// Gyro bias drift e1, e2 in deg/s/degC, deg/s/degC^2.
    pub gyro_bias_dps: [Vec3<f32>; 2],
}

impl ThermalDrift {
    /// A typical part.
    // NOTE: zero-g drift. The Product Specification (rev 3.4, table 6.2) bounds the zero-g level
    // change over 0-70 degC to +-35 mg (x, y) and +-60 mg (z); flight-controller users measure
    // 0.7-2.2 mg/degC. 0.75, -0.7 and 1.4 mg/degC with a little curvature stay inside the
    // datasheet's bounds about the middle of that range (checked by a test).
    // NOTE: sensitivity drift. Table 6.2 gives +-0.02 %/degC; 0.012-0.016 %/degC is inside it.
    // NOTE: gyro bias drift. Table 6.1 gives +-20 deg/s over -40 to +85 degC (0.16 deg/s/degC at
    // most); measured parts move 0.04-0.09 deg/s/degC.
    pub const fn typical() -> Self {
        ThermalDrift {
            offset_g: [[0.75e-3, -0.7e-3, 1.4e-3], [4e-6, 3e-6, -6e-6]],
            scale: [[1.2e-4, -0.8e-4, 1.6e-4], [5e-7, 0.0, -5e-7]],
            gyro_bias_dps: [[0.05, -0.07, 0.04], [4e-4, -3e-4, 5e-4]],
        }
    }

    /// No drift at all.
    pub const fn none() -> Self {
        ThermalDrift { offset_g: [[0.0; 3]; 2], scale: [[0.0; 3]; 2], gyro_bias_dps: [[0.0; 3]; 2] }
    }

    /// The true errors at the true die temperature `die_c`: o(T), M(T) = M diag(1 + d(T))^-1, b(T).
    pub fn at(&self, truth: &TrueErrors, die_c: f32) -> TrueErrors {
        let dt = die_c - TRUTH_REF_TEMP_C;
        let poly = |c: &[Vec3<f32>; 2]| [0, 1, 2].map(|k| c[0][k] * dt + c[1][k] * dt * dt);
        let scale = poly(&self.scale);
        let mut matrix = truth.matrix;
        for row in matrix.iter_mut() {
            for (col, value) in row.iter_mut().enumerate() {
                *value /= 1.0 + scale[col];
            }
        }
        TrueErrors {
            matrix,
            offset_g: linalg::add(truth.offset_g, poly(&self.offset_g)),
            gyro_bias_dps: linalg::add(truth.gyro_bias_dps, poly(&self.gyro_bias_dps)),
            gyro_matrix: truth.gyro_matrix,
        }
    }
}

#[cfg(test)]
mod tests;
