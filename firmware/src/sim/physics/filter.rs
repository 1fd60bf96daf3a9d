//! The accelerometer's own low-pass filter on the MPU-6500 family (ACCEL_CONFIG2), as it shapes the
//! white noise: a one-pole filter whose noise bandwidth is the configured bandwidth.
//!
//! NOTE: white noise of one-sided density n through a one-pole low-pass of noise bandwidth B has a
//! standard deviation of n sqrt(B) and a correlation time of 1 / (4 B) (the one-pole's noise
//! bandwidth is pi/2 times its corner, 1 / (4 tau)). Sampled every dt, it is exactly the
//! first-order autoregression below, so the filter costs one draw per sample at any sample rate,
//! and a rate below twice the bandwidth aliases the noise as the real sensor's decimation does.

use shared::linalg::{self, Vec3};

use super::{Physics, ACCEL_NOISE_DENSITY_G};

impl Physics {
    /// The filtered accelerometer noise one sample period `dt_s` after the last, in g.
    pub(super) fn filtered_accel_noise(&mut self, bandwidth_hz: f32, dt_s: f32) -> Vec3<f32> {
        let sigma = ACCEL_NOISE_DENSITY_G * libm::sqrtf(bandwidth_hz);
        let Some(state) = self.accel_filter_state else {
            // The filter has run since power-on: its output is already stationary.
            let start = self.noise(sigma);
            self.accel_filter_state = Some(start);
            return start;
        };
        let keep = libm::expf(-dt_s * 4.0 * bandwidth_hz);
        let fresh = self.noise(sigma * libm::sqrtf(1.0 - keep * keep));
        let next = linalg::add(linalg::scale(state, keep), fresh);
        self.accel_filter_state = Some(next);
        next
    }
}
