//! The capture engine: averages the still sensor over 5-20 s, or until its mean is known well enough
//! (a [`CaptureGoal`]), exactly, from FIFO samples.
//!
//! Sums and sums of squares are kept in integers, so the statistics do not depend on the order or
//! the number of samples; the result carries mean and scatter, and the capture is refused when the
//! scatter shows motion or a sample hit the end of the range.

use shared::protocol::{
    CaptureGoal, CaptureProgress, CaptureStats, DeviceError, SensorConfig, MAX_CAPTURE_SECONDS, MAX_STILL_ACCEL_STD_G,
    MAX_STILL_GYRO_STD_DPS, MIN_CAPTURE_SECONDS, MIN_GOAL_SAMPLES,
};

use crate::sensor::registers::{temp_c, GYRO_LSB_PER_DPS, GYRO_OUTPUT_RATE_HZ};
use crate::sensor::RawSample;

/// The most samples a capture can sum: its longest at the sensor's fastest rate.
const MOST_CAPTURE_SAMPLES: i64 = MAX_CAPTURE_SECONDS as i64 * GYRO_OUTPUT_RATE_HZ as i64;

// NOTE: n * sum(x^2) <= n^2 * 2^30 for 16-bit samples; it must stay below i64::MAX for `Sums::std`.
const _: () = assert!(MOST_CAPTURE_SAMPLES * MOST_CAPTURE_SAMPLES < i64::MAX >> 30);

/// Integer sums over the samples of a capture.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct Sums {
    count: u32,
    accel: [i64; 3],
    accel_squares: [i64; 3],
    gyro: [i64; 3],
    gyro_squares: [i64; 3],
    temp: i64,
    clipped: u32,
}

impl Sums {
    fn add(&mut self, sample: &RawSample) {
        self.count += 1;
        for axis in 0..3 {
            let (a, g) = (i64::from(sample.accel[axis]), i64::from(sample.gyro[axis]));
            self.accel[axis] += a;
            self.accel_squares[axis] += a * a;
            self.gyro[axis] += g;
            self.gyro_squares[axis] += g * g;
        }
        self.temp += i64::from(sample.temp);
        if sample.accel.iter().any(|&a| a == i16::MAX || a == i16::MIN) {
            self.clipped += 1;
        }
    }

    /// Exact mean of a sum, in LSB: integer quotient plus the remainder's fraction.
    fn mean(&self, sum: i64) -> f32 {
        let n = i64::from(self.count.max(1));
        (sum.div_euclid(n)) as f32 + (sum.rem_euclid(n)) as f32 / n as f32
    }

    /// Sample standard deviation in LSB, from an exact integer numerator n*sum(x^2) - sum(x)^2.
    ///
    /// NOTE: exact in 64 bits: see [`MOST_CAPTURE_SAMPLES`] (128-bit arithmetic cost the Pico 500 B).
    fn std(&self, sum: i64, squares: i64) -> f32 {
        let n = i64::from(self.count);
        if n < 2 {
            return 0.0;
        }
        let numerator = n * squares - sum * sum;
        libm::sqrtf(numerator as f32 / (n * (n - 1)) as f32)
    }

    /// Whether every accelerometer axis' mean has a standard error (std / sqrt(n)) of at most
    /// `mean_std_lsb`.
    fn means_known(&self, mean_std_lsb: f32) -> bool {
        let bound = mean_std_lsb * libm::sqrtf(self.count as f32);
        (0..3).all(|k| self.std(self.accel[k], self.accel_squares[k]) <= bound)
    }
}

/// A stop rule: the standard error of the means to reach, in LSB, from `min_samples` on.
#[derive(Debug, Clone, Copy, PartialEq)]
struct StopRule {
    mean_std_lsb: f32,
    min_samples: u32,
}

/// A capture in progress.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Capture {
    sums: Sums,
    total_samples: u32,
    config: SensorConfig,
    rule: Option<StopRule>,
}

impl Capture {
    /// A capture of `seconds` (5-20) at the sensor's configured rate.
    pub fn new(seconds: u8, config: SensorConfig) -> Result<Self, DeviceError> {
        if !(MIN_CAPTURE_SECONDS..=MAX_CAPTURE_SECONDS).contains(&seconds) {
            return Err(DeviceError::InvalidDuration { seconds });
        }
        let total_samples = u32::from(seconds) * u32::from(config.sample_rate_hz);
        Ok(Capture { sums: Sums::default(), total_samples, config, rule: None })
    }

    /// A capture that stops at `goal` (at most [`MAX_CAPTURE_SECONDS`] at the configured rate).
    pub fn until(goal: CaptureGoal, config: SensorConfig) -> Result<Self, DeviceError> {
        let most = u32::from(MAX_CAPTURE_SECONDS) * u32::from(config.sample_rate_hz);
        let CaptureGoal { mean_std_g, min_samples, max_samples } = goal;
        // NOTE: written so that a NaN goal fails the test too.
        let positive = mean_std_g > 0.0;
        if !positive || min_samples < MIN_GOAL_SAMPLES || max_samples > most || min_samples > max_samples {
            return Err(DeviceError::InvalidGoal);
        }
        let rule = StopRule { mean_std_lsb: mean_std_g * config.range.lsb_per_g(), min_samples };
        Ok(Capture { sums: Sums::default(), total_samples: max_samples, config, rule: Some(rule) })
    }

    /// Samples the capture averages in all: rate x seconds.
    pub fn total_samples(&self) -> u32 {
        self.total_samples
    }

    /// Samples taken so far.
    pub fn samples(&self) -> u32 {
        self.sums.count
    }

    /// Takes samples up to the capture's most; returns how many it took. A stop rule is judged
    /// after each call ([`Self::is_complete`]): the engine hands over one FIFO read (at most 16
    /// samples) at a time.
    pub fn take(&mut self, samples: &[RawSample]) -> usize {
        let room = (self.total_samples - self.sums.count) as usize;
        let taken = samples.len().min(room);
        samples[..taken].iter().for_each(|s| self.sums.add(s));
        taken
    }

    /// Whether every sample has been taken, or the stop rule is met.
    pub fn is_complete(&self) -> bool {
        let known = |r: &StopRule| self.sums.count >= r.min_samples && self.sums.means_known(r.mean_std_lsb);
        self.sums.count >= self.total_samples || self.rule.as_ref().is_some_and(known)
    }

    /// Progress for the host's display.
    pub fn progress(&self) -> CaptureProgress {
        let lsb = self.config.range.lsb_per_g();
        CaptureProgress {
            samples: self.sums.count,
            total_samples: self.total_samples,
            mean_g: [0, 1, 2].map(|axis| self.sums.mean(self.sums.accel[axis]) / lsb),
        }
    }

    /// The statistics, or why the capture cannot be used (clipped, moved).
    pub fn finish(&self) -> Result<CaptureStats, DeviceError> {
        let stats = self.stats();
        if stats.clipped > 0 {
            return Err(DeviceError::Clipped { samples: stats.clipped });
        }
        let accel_std = stats.std_g.iter().copied().fold(0.0, f32::max);
        let gyro_std = stats.gyro_std_dps.iter().copied().fold(0.0, f32::max);
        if accel_std > MAX_STILL_ACCEL_STD_G || gyro_std > MAX_STILL_GYRO_STD_DPS {
            return Err(DeviceError::Moved { accel_std_mg: accel_std * 1000.0, gyro_std_dps: gyro_std });
        }
        Ok(stats)
    }

    /// The statistics of the samples taken, whatever they show.
    pub fn stats(&self) -> CaptureStats {
        let s = &self.sums;
        let lsb = self.config.range.lsb_per_g();
        CaptureStats {
            samples: s.count,
            seconds: s.count as f32 / f32::from(self.config.sample_rate_hz),
            mean_g: [0, 1, 2].map(|k| s.mean(s.accel[k]) / lsb),
            std_g: [0, 1, 2].map(|k| s.std(s.accel[k], s.accel_squares[k]) / lsb),
            gyro_mean_dps: [0, 1, 2].map(|k| s.mean(s.gyro[k]) / GYRO_LSB_PER_DPS),
            gyro_std_dps: [0, 1, 2].map(|k| s.std(s.gyro[k], s.gyro_squares[k]) / GYRO_LSB_PER_DPS),
            temp_c: temp_c(s.mean(s.temp)),
            clipped: s.clipped,
            range: self.config.range,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample(accel: [i16; 3], gyro: [i16; 3]) -> RawSample {
        RawSample { accel, temp: -3536, gyro }
    }

    #[test]
    fn refuses_durations_outside_5_to_20_seconds() {
        for seconds in [0, 4, 21, 255] {
            assert_eq!(Capture::new(seconds, SensorConfig::default()), Err(DeviceError::InvalidDuration { seconds }));
        }
        assert_eq!(Capture::new(5, SensorConfig::default()).unwrap().total_samples(), 500);
        assert_eq!(Capture::new(20, SensorConfig::default()).unwrap().total_samples(), 2000);
    }

    #[test]
    fn statistics_are_exact_for_known_samples() {
        let mut capture = Capture::new(5, SensorConfig::default()).unwrap();
        // Alternating 16384 +- 100 on z: mean 1 g, std 100 LSB * sqrt(n / (n - 1)).
        let samples: Vec<_> =
            (0..500).map(|i| sample([0, 1, 16384 + if i % 2 == 0 { 100 } else { -100 }], [164, 0, -328])).collect();
        assert_eq!(capture.take(&samples), 500);
        assert!(capture.is_complete());
        let stats = capture.finish().unwrap();
        assert_eq!(stats.samples, 500);
        assert_eq!(stats.seconds, 5.0);
        assert_eq!(stats.mean_g, [0.0, 1.0 / 16384.0, 1.0]);
        let expected_std = 100.0 * (500.0f32 / 499.0).sqrt() / 16384.0;
        assert!((stats.std_g[2] - expected_std).abs() < 1e-7, "{}", stats.std_g[2]);
        assert_eq!(stats.std_g[0], 0.0);
        // 32.8 LSB per deg/s at +-1000 deg/s (Product Specification 6.1).
        assert_eq!(stats.gyro_mean_dps, [5.0, 0.0, -10.0]);
        assert!((stats.temp_c - 26.13).abs() < 0.01);
    }

    #[test]
    fn the_longest_capture_at_the_fastest_rate_of_full_scale_samples_has_its_exact_scatter() {
        let mut sums = Sums::default();
        for i in 0..MOST_CAPTURE_SAMPLES {
            sums.add(&sample([0, 0, 16384], [if i % 2 == 0 { i16::MIN } else { i16::MAX }; 3]));
        }
        // Alternating -32768 and 32767: 32767.5 LSB about -0.5, times sqrt(n / (n - 1)).
        let n = MOST_CAPTURE_SAMPLES as f64;
        let expected_lsb = 32767.5 * (n / (n - 1.0)).sqrt();
        let scatter_lsb = f64::from(sums.std(sums.gyro[0], sums.gyro_squares[0]));
        assert!((scatter_lsb - expected_lsb).abs() < 1e-6 * expected_lsb, "{scatter_lsb} LSB, want {expected_lsb}");
    }

    #[test]
    fn takes_no_more_than_rate_times_seconds() {
        let mut capture = Capture::new(5, SensorConfig::default()).unwrap();
        let samples = vec![sample([0, 0, 16384], [0; 3]); 300];
        assert_eq!(capture.take(&samples), 300);
        assert_eq!(capture.take(&samples), 200);
        assert_eq!(capture.take(&samples), 0);
        assert_eq!(capture.samples(), 500);
    }

    /// Samples alternating +-`half` LSB about 1 g on z: standard deviation `half` (a little more).
    fn alternating(count: usize, half: i16) -> Vec<RawSample> {
        (0..count).map(|i| sample([0, 0, 16384 + if i % 2 == 0 { half } else { -half }], [0; 3])).collect()
    }

    #[test]
    fn a_goal_stops_the_capture_once_every_mean_is_known_that_well() {
        // Scatter 48 LSB (2.93 mg): the standard error of the mean reaches 0.25 mg = 4.096 LSB when
        // sqrt(n) >= 48 * sqrt(n / (n - 1)) / 4.096, at n = 139.
        // Fed 16 at a time, as the engine reads the FIFO: it stops with the read that gets there.
        let goal = CaptureGoal { mean_std_g: 0.25e-3, min_samples: 20, max_samples: 2000 };
        let mut capture = Capture::until(goal, SensorConfig::default()).unwrap();
        let samples = alternating(1000, 48);
        let mut batches = samples.chunks(16);
        while !capture.is_complete() {
            capture.take(batches.next().unwrap());
        }
        assert_eq!(capture.samples(), 144);
        let stats = capture.finish().unwrap();
        assert!(stats.std_g[2] / (stats.samples as f32).sqrt() <= 0.25e-3, "{stats:?}");
    }

    #[test]
    fn a_goal_waits_for_its_minimum_and_stops_at_its_maximum() {
        let config = SensorConfig::default();
        let still = CaptureGoal { mean_std_g: 1.0, min_samples: 50, max_samples: 60 };
        let mut capture = Capture::until(still, config).unwrap();
        capture.take(&alternating(49, 48));
        assert!(!capture.is_complete(), "49 samples, before the minimum");
        capture.take(&alternating(1, 48));
        assert!(capture.is_complete(), "50 samples, the minimum");
        let unreachable = CaptureGoal { mean_std_g: 1e-6, min_samples: 20, max_samples: 60 };
        let mut capture = Capture::until(unreachable, config).unwrap();
        assert_eq!(capture.take(&alternating(100, 48)), 60);
        assert!(capture.is_complete());
    }

    #[test]
    fn goals_outside_their_limits_are_refused() {
        let config = SensorConfig::default();
        for (mean_std_g, min_samples, max_samples) in
            [(0.0, 20, 100), (f32::NAN, 20, 100), (1e-4, 19, 100), (1e-4, 101, 100), (1e-4, 20, 2001)]
        {
            let goal = CaptureGoal { mean_std_g, min_samples, max_samples };
            assert_eq!(Capture::until(goal, config), Err(DeviceError::InvalidGoal), "{goal:?}");
        }
        assert!(Capture::until(CaptureGoal { mean_std_g: 1e-4, min_samples: 20, max_samples: 2000 }, config).is_ok());
    }

    #[test]
    fn a_saturated_sample_refuses_the_capture_as_clipped() {
        let mut capture = Capture::new(5, SensorConfig::default()).unwrap();
        let mut samples = vec![sample([0, 0, 16384], [0; 3]); 500];
        samples[17].accel[0] = i16::MIN;
        samples[400].accel[1] = i16::MAX;
        capture.take(&samples);
        assert_eq!(capture.finish(), Err(DeviceError::Clipped { samples: 2 }));
    }
}
