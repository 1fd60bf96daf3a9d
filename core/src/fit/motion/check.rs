//! Whether a session can be fitted with its motion, and the still-period fit when it cannot: every
//! sample with its gyro sample, none lost, none clipped, fast enough (issue 38 (5)).

use std::fmt;

use super::{fit_joint, JointFit, MotionData};
use crate::data::{Dataset, Row};
use crate::fit::{fit, Fit, FitError, FitOptions, ModelChoice};
use crate::limits::{MOTION_MIN_RATE_HZ, MOTION_MIN_RESTS};

/// The fraction of the range's full scale at which a reading counts as clipped: the largest count,
/// 32767 of 32768 (a signed 16-bit register).
const CLIPPED_FRACTION: f64 = 32767.0 / 32768.0;

/// Why a session's motion cannot be used, with the way out.
#[derive(Debug, Clone, PartialEq)]
pub enum Unusable {
    /// The board sent no gyro samples.
    NoGyro,
    /// Fewer gyro samples than accelerometer samples.
    UnpairedGyro { accel: usize, gyro: usize },
    /// The samples come too slowly, in Hz.
    TooSlow { rate_hz: f64 },
    /// Samples were lost: `lost` in all, the first after sample `after`.
    Gaps { lost: u64, after: u64 },
    /// Readings at the range's full scale during a turn (the turn's integral is wrong).
    Clipped { samples: usize },
    /// Too few rests.
    TooFewRests { rests: usize },
    /// The joint fit did not converge.
    Diverged,
}

impl fmt::Display for Unusable {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Unusable::NoGyro => write!(f, "the stream has no gyro samples: stream the gyro with the accelerometer to use the motion"),
            Unusable::UnpairedGyro { accel, gyro } => write!(f, "{gyro} gyro samples for {accel} accelerometer samples: every accelerometer sample needs its gyro sample"),
            Unusable::TooSlow { rate_hz } => write!(f, "{rate_hz} Hz is below the {MOTION_MIN_RATE_HZ} Hz the motion needs: stream faster (1 kHz is best)"),
            Unusable::Gaps { lost, after } => write!(f, "{lost} samples were lost (the first after sample {after}): a turn's integral needs every sample; use a faster link or a lower rate"),
            Unusable::Clipped { samples } => write!(f, "{samples} readings reached the range's full scale: turn more gently, or choose a wider range"),
            Unusable::TooFewRests { rests } => write!(f, "only {rests} rests; the motion fit needs {MOTION_MIN_RESTS}: keep turning and pausing"),
            Unusable::Diverged => write!(f, "the joint fit did not converge: the turns do not agree with the rests (was the board put down between them?)"),
        }
    }
}

/// What a session yields: the joint fit, or the still periods' fit and why.
#[derive(Debug, Clone, PartialEq)]
pub enum MotionOutcome {
    /// The joint fit.
    Joint(Box<JointFit>),
    /// The still periods alone, fitted as a data file of their means would be.
    Still { reason: Unusable, fit: Box<Result<Fit, FitError>> },
}

/// Whether `data` can be fitted with its motion.
pub fn usable(data: &MotionData) -> Result<(), Unusable> {
    if data.gyro_dps.is_empty() {
        return Err(Unusable::NoGyro);
    }
    if data.gyro_dps.len() != data.accel_g.len() {
        return Err(Unusable::UnpairedGyro { accel: data.accel_g.len(), gyro: data.gyro_dps.len() });
    }
    if data.rate_hz < MOTION_MIN_RATE_HZ {
        return Err(Unusable::TooSlow { rate_hz: data.rate_hz });
    }
    gaps(data)?;
    let clipped = |v: &nalgebra::Vector3<f64>, full: f64| v.amax() >= full * CLIPPED_FRACTION;
    let samples = data.accel_g.iter().filter(|m| clipped(m, data.accel_full_scale_g)).count()
        + data.gyro_dps.iter().filter(|w| clipped(w, data.gyro_full_scale_dps)).count();
    if samples > 0 {
        return Err(Unusable::Clipped { samples });
    }
    if data.rests.len() < MOTION_MIN_RESTS {
        return Err(Unusable::TooFewRests { rests: data.rests.len() });
    }
    Ok(())
}

/// The first gap in the sequence numbers, with the count of every sample lost.
fn gaps(data: &MotionData) -> Result<(), Unusable> {
    let steps = data.indices.windows(2).filter(|w| w[1] != w[0] + 1);
    let lost: u64 = steps.clone().map(|w| w[1].saturating_sub(w[0] + 1).max(1)).sum();
    match steps.map(|w| w[0]).next() {
        Some(after) => Err(Unusable::Gaps { lost, after }),
        None => Ok(()),
    }
}

/// The joint fit when `data` allows it, else the still periods' fit with the reason.
pub fn fit_or_fall_back(data: &MotionData) -> MotionOutcome {
    let reason = match usable(data).map(|()| fit_joint(data)) {
        Ok(Some(joint)) => return MotionOutcome::Joint(Box::new(joint)),
        Ok(None) => Unusable::Diverged,
        Err(reason) => reason,
    };
    MotionOutcome::Still { reason, fit: Box::new(fit(&still_rows(data), ModelChoice::Auto, &FitOptions::default())) }
}

/// Each rest's mean reading as a data row with its sample count.
fn still_rows(data: &MotionData) -> Dataset {
    let rows = data.rests.iter().enumerate().map(|(k, rest)| {
        let mean = data.accel_g[rest.clone()].iter().sum::<nalgebra::Vector3<f64>>() / rest.len() as f64;
        Row { count: u32::try_from(rest.len()).ok(), ..Row::new(k + 2, mean.into(), None) }
    });
    Dataset { rows: rows.collect() }
}
