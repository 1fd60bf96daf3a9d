//! The mean output of a board that must rest: a raw stream's samples after the output settled,
//! averaged per axis, or why the board counts as moved. The datasheet self-test and the family's
//! offset check both measure this way.

use shared::protocol::{Sample, StreamKind, MAX_STILL_ACCEL_STD_G, MAX_STILL_GYRO_STD_DPS};

use crate::link::{Client, LinkError, Port, StreamRequest};

/// One stretch of a raw stream to average.
#[derive(Debug, Clone, Copy)]
pub struct StillPhase {
    /// The phase's name in a message ("self-test on").
    pub label: &'static str,
    /// The stream's rate, in Hz (it must divide the board's sample rate).
    pub rate_hz: u16,
    /// Samples passed over first, while the output settles after a register changed.
    pub settle: usize,
    /// Samples averaged after them.
    pub samples: usize,
    /// The true rate in deg/s of a rate the board reports as 1 deg/s (not 1 when the gyro runs at
    /// another range than the board converts with).
    pub gyro_dps_per_reported: f64,
}

/// Why a phase gave no mean.
#[derive(Debug, thiserror::Error)]
pub enum StillError {
    #[error(transparent)]
    Link(#[from] LinkError),
    #[error("only {received} of {wanted} samples of the {phase} phase arrived: check the cable and run again")]
    TooFewSamples { phase: &'static str, received: usize, wanted: usize },
}

impl StillPhase {
    /// Streams the phase: the mean of each axis (accelerometer in g, gyro in deg/s as the board
    /// reports them), or why the board counts as moved.
    pub fn mean<P: Port>(&self, client: &mut Client<P>) -> Result<Result<[f64; 6], String>, StillError> {
        let wanted =
            StreamRequest { kind: StreamKind::Raw, rate_hz: self.rate_hz, count: (self.settle + self.samples) as u32 };
        let mut samples = Vec::with_capacity(self.samples);
        client.stream(wanted, |sample| {
            if sample.index as usize >= self.settle {
                samples.push(*sample);
            }
        })?;
        // NOTE: a lost sample does not bias a mean; only too few of them make it uncertain.
        if samples.len() < self.samples * 9 / 10 {
            let (phase, received, wanted) = (self.label, samples.len(), self.samples);
            return Err(StillError::TooFewSamples { phase, received, wanted });
        }
        Ok(self.still_mean(&samples))
    }

    /// The mean of each axis, or why the board counts as moved: an axis scattered more than a still
    /// board's ([`MAX_STILL_ACCEL_STD_G`], [`MAX_STILL_GYRO_STD_DPS`]).
    fn still_mean(&self, samples: &[Sample]) -> Result<[f64; 6], String> {
        let values = |axis: usize| {
            samples.iter().map(move |s| f64::from(if axis < 3 { s.accel_g[axis] } else { s.gyro_dps[axis - 3] }))
        };
        let n = samples.len() as f64;
        let mean: [f64; 6] = core::array::from_fn(|axis| values(axis).sum::<f64>() / n);
        let scatter = |axis: usize| (values(axis).map(|v| (v - mean[axis]).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
        let accel_std_g = (0..3).map(scatter).fold(0.0, f64::max);
        let gyro_std_dps = (3..6).map(scatter).fold(0.0, f64::max) * self.gyro_dps_per_reported;
        if accel_std_g > f64::from(MAX_STILL_ACCEL_STD_G) || gyro_std_dps > f64::from(MAX_STILL_GYRO_STD_DPS) {
            return Err(format!("the output scattered by {:.1} mg and {gyro_std_dps:.2} deg/s", accel_std_g * 1e3));
        }
        Ok(mean)
    }
}
