//! The chip's temperature bins: every sample the capture and stream engine takes is added, in
//! integers, to the bin of its whole degree of die temperature, so a board left to warm or cool
//! learns its drift from every sample rather than from one mean per capture. The host takes the
//! bins (and so empties them) after each capture.

use shared::protocol::{TempBin, TEMP_BINS_PER_MESSAGE};
use shared::AccelRange;

use crate::sensor::registers::{temp_c, GYRO_LSB_PER_DPS};
use crate::sensor::RawSample;

/// The coolest bin, in degC.
pub const FIRST_DEGREE_C: i8 = -10;
/// Bins kept: one per degree from [`FIRST_DEGREE_C`] up to 69 degC.
///
/// NOTE: 80 bins cover the datasheet's 0-70 degC (and a freezer bag's -10): 80 x 32 bytes of RAM;
/// a sample outside falls in the end bins.
pub const BIN_COUNT: usize = 80;
/// Samples a bin sums at most: 65 535 of at most 32 768 LSB stay within an i32.
///
/// NOTE: i32 sums halve the store against i64; a full bin is 65 s of one degree at 1 kHz, longer
/// than the host leaves between takes while learning, and its later samples add nothing new.
pub const MAX_BIN_SAMPLES: u32 = u16::MAX as u32;

/// Integer sums of one bin (LSB).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct Sums {
    samples: u32,
    temp: i32,
    accel: [i32; 3],
    gyro: [i32; 3],
}

/// The bins of the samples taken since the host last took them.
#[derive(Debug, Clone, PartialEq)]
pub struct TemperatureBins {
    bins: [Sums; BIN_COUNT],
}

impl Default for TemperatureBins {
    fn default() -> Self {
        TemperatureBins { bins: [Sums::default(); BIN_COUNT] }
    }
}

impl TemperatureBins {
    /// Adds samples to the bins of their die temperatures.
    pub fn add(&mut self, samples: &[RawSample]) {
        for sample in samples {
            let temp_c = temp_c(f32::from(sample.temp));
            let index = (libm::floorf(temp_c) as i32 - i32::from(FIRST_DEGREE_C)).clamp(0, BIN_COUNT as i32 - 1);
            let bin = &mut self.bins[index as usize];
            if bin.samples >= MAX_BIN_SAMPLES {
                continue;
            }
            bin.samples += 1;
            bin.temp += i32::from(sample.temp);
            for axis in 0..3 {
                bin.accel[axis] += i32::from(sample.accel[axis]);
                bin.gyro[axis] += i32::from(sample.gyro[axis]);
            }
        }
    }

    /// Forgets every bin (the range changed: the sums would mix scales).
    pub fn clear(&mut self) {
        *self = TemperatureBins::default();
    }

    /// Hands over the coolest non-empty bins, at most [`TEMP_BINS_PER_MESSAGE`], and empties them;
    /// accelerometer sums are read at `range`.
    pub fn take(&mut self, range: AccelRange) -> heapless::Vec<TempBin, TEMP_BINS_PER_MESSAGE> {
        let mut taken = heapless::Vec::new();
        for (index, bin) in self.bins.iter_mut().enumerate().filter(|(_, bin)| bin.samples > 0) {
            if taken.push(message(index, bin, range)).is_err() {
                break;
            }
            *bin = Sums::default();
        }
        taken
    }
}

/// A bin as its message: means in g, deg/s and degC.
fn message(index: usize, bin: &Sums, range: AccelRange) -> TempBin {
    let n = bin.samples as f32;
    let mean = |sum: i32| sum as f32 / n;
    TempBin {
        degree_c: FIRST_DEGREE_C + index as i8,
        samples: bin.samples,
        temp_c: temp_c(mean(bin.temp)),
        accel_g: bin.accel.map(|sum| mean(sum) / range.lsb_per_g()),
        gyro_dps: bin.gyro.map(|sum| mean(sum) / GYRO_LSB_PER_DPS),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sample at the raw temperature `temp` reading `z` LSB on accel z and `gx` on gyro x.
    fn sample(temp: i16, z: i16, gx: i16) -> RawSample {
        RawSample { accel: [0, 0, z], temp, gyro: [gx, 0, 0] }
    }

    /// The raw TEMP_OUT of `temp_c` (register map 4.18: raw / 340 + 36.53).
    fn raw_temp(temp_c: f32) -> i16 {
        ((temp_c - 36.53) * 340.0).round() as i16
    }

    #[test]
    fn samples_fall_in_the_bin_of_their_whole_degree_and_are_averaged_there() {
        let mut bins = TemperatureBins::default();
        let warm = [sample(raw_temp(25.2), 16384, 131), sample(raw_temp(25.8), 16484, 393)];
        bins.add(&warm);
        bins.add(&[sample(raw_temp(26.5), 16000, 0), sample(raw_temp(-30.0), 0, 0)]);
        let taken = bins.take(AccelRange::G2);
        assert_eq!(taken.iter().map(|b| (b.degree_c, b.samples)).collect::<Vec<_>>(), [(-10, 1), (25, 2), (26, 1)]);
        let bin = taken[1];
        assert!((bin.temp_c - 25.5).abs() < 0.01, "{bin:?}");
        assert_eq!(bin.accel_g, [0.0, 0.0, 16434.0 / 16384.0]);
        assert_eq!(bin.gyro_dps, [262.0 / GYRO_LSB_PER_DPS, 0.0, 0.0]);
        assert!(bins.take(AccelRange::G2).is_empty(), "taking empties the bins");
    }

    #[test]
    fn a_full_bin_takes_no_more_samples_and_its_sums_do_not_overflow() {
        let mut bins = TemperatureBins::default();
        let extreme = vec![sample(raw_temp(30.5), i16::MIN, i16::MIN); 70_000];
        bins.add(&extreme);
        let taken = bins.take(AccelRange::G2);
        assert_eq!(
            (taken[0].samples, taken[0].accel_g[2], taken[0].gyro_dps[0]),
            (MAX_BIN_SAMPLES, -2.0, -32768.0 / GYRO_LSB_PER_DPS)
        );
    }

    #[test]
    fn a_take_hands_over_at_most_one_message_of_bins_and_keeps_the_rest() {
        let mut bins = TemperatureBins::default();
        let spread: Vec<RawSample> = (0..10).map(|d| sample(raw_temp(20.5 + d as f32), 16384, 0)).collect();
        bins.add(&spread);
        let first = bins.take(AccelRange::G2);
        assert_eq!(first.iter().map(|b| b.degree_c).collect::<Vec<_>>(), [20, 21, 22, 23, 24, 25]);
        let rest = bins.take(AccelRange::G2);
        assert_eq!(rest.iter().map(|b| b.degree_c).collect::<Vec<_>>(), [26, 27, 28, 29]);
    }
}
