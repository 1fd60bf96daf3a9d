//! What a stream costs the calibration, in numbers: noise folded in by a low rate with a wide
//! low-pass, values printed with too few decimals, samples lost where nobody can see them.

use serde::Serialize;

use super::log::StreamLog;
use super::segment::Segment;
use super::timing::{lost_in_gaps, RateSource};
use crate::limits::FOLDED_NOISE_FACTOR;

/// The MPU-6050's accelerometer noise density, in g/sqrt(Hz) (Product Specification 6.2).
const ACCEL_DENSITY_G: f64 = 400e-6;
/// The accelerometer low-pass settings of the MPU-6050, in Hz (register map 4.3, DLPF_CFG 0-6).
const LOW_PASS_HZ: [f64; 7] = [260.0, 184.0, 94.0, 44.0, 21.0, 10.0, 5.0];
/// A position's mean known to this, in g, is what the capture times below are for.
const MEAN_GOAL_G: f64 = 1e-4;

/// One cost of the stream.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Cost {
    /// `aliasing`, `decimals`, `no-timestamps`, `lost`.
    pub kind: &'static str,
    /// What it costs, in words with numbers.
    pub words: String,
}

/// Every cost of `log`, judged from its still `segments`.
pub fn costs(log: &StreamLog, segments: &[Segment]) -> Vec<Cost> {
    let mut costs = Vec::new();
    let scatter_g = median(segments.iter().map(|s| rms(s.std_g)));
    costs.extend(scatter_g.and_then(|s| aliasing(log, s)));
    costs.extend(accel_decimals(log, scatter_g));
    costs.extend(gyro_decimals(log, segments));
    costs.extend(timestamps(log));
    costs
}

fn aliasing(log: &StreamLog, scatter_g: f64) -> Option<Cost> {
    let rate = log.rate?.hz;
    let band_hz = (scatter_g / ACCEL_DENSITY_G).powi(2);
    if band_hz < FOLDED_NOISE_FACTOR * rate / 2.0 {
        return None;
    }
    let here_s = (scatter_g / MEAN_GOAL_G).powi(2) / mutant!("cost-here-time-doubled", rate, rate / 2.0);
    let low_pass =
        LOW_PASS_HZ.into_iter().find(|&f| f <= mutant!("cost-low-pass-above-nyquist", rate / 2.0, rate)).unwrap_or(5.0);
    // NOTE: with the band within the rate, a mean over T seconds scatters density / sqrt(2 T), however
    // narrow the low-pass: the time no longer depends on the rate.
    let filtered_s = (ACCEL_DENSITY_G / MEAN_GOAL_G).powi(2) / mutant!("cost-filtered-time-unhalved", 2.0, 1.0);
    Some(Cost {
        kind: "aliasing",
        words: format!(
            "each sample scatters {:.1} mg: the sketch reads single samples of a signal about {band_hz:.0} Hz wide \
             at {rate:.0} Hz, so the noise of the whole band folds in; a position known to 0.1 mg takes {here_s:.0} s \
             here, {filtered_s:.0} s with the chip's low-pass at {low_pass:.0} Hz (DLPF_CFG in register 0x1A)",
            scatter_g * 1e3
        ),
    })
}

fn accel_decimals(log: &StreamLog, scatter_g: Option<f64>) -> Option<Cost> {
    let step_g = step(log.samples.iter().flat_map(|s| s.accel))? / log.accel_unit.per_g();
    (step_g > scatter_g? / 2.0).then(|| Cost {
        kind: "decimals",
        words: format!(
            "the accelerometer's values step by {:.2} mg, more than half their scatter ({:.2} mg): print more decimals",
            step_g * 1e3,
            scatter_g.unwrap_or(0.0) * 1e3
        ),
    })
}

fn gyro_decimals(log: &StreamLog, segments: &[Segment]) -> Option<Cost> {
    let (unit, _) = log.gyro_unit?;
    let step_dps = step(log.samples.iter().filter_map(|s| s.gyro).flatten())? / unit.per_dps();
    let gyro = log.gyro_dps()?;
    let scatter = median(segments.iter().map(|s| rms(super::segment::mean_std(&gyro[s.first..=s.last]).1)))?;
    (step_dps > scatter).then(|| Cost {
        kind: "decimals",
        words: format!(
            "the gyro's values step by {step_dps:.2} deg/s, more than its noise ({scatter:.3} deg/s): its bias is known \
             no better than {:.2} deg/s; print more decimals",
            mutant!("cost-gyro-bias-whole-step", step_dps / 2.0, step_dps)
        ),
    })
}

fn timestamps(log: &StreamLog) -> Option<Cost> {
    if log.layout.columns.time.is_none() {
        let rate = match log.rate {
            Some(rate) if rate.source == RateSource::Given => format!("{:.1} Hz, from --rate", rate.hz),
            Some(rate) => format!("{:.1} Hz, from the lines' arrival", rate.hz),
            None => "unknown".to_owned(),
        };
        let words = format!("no timestamps: a lost line cannot be seen, and the rate is {rate}");
        return Some(Cost { kind: "no-timestamps", words });
    }
    let rate = log.rate?;
    let times: Vec<f64> = log.samples.iter().filter_map(|s| s.time).collect();
    let lost = lost_in_gaps(&times, rate);
    (lost > 0).then(|| Cost {
        kind: "lost",
        words: format!("the timestamps show {} samples lost in gaps", mutant!("cost-lost-one-short", lost, lost - 1)),
    })
}

/// The step the values are printed in: 10^-d for the most decimals any value has (d <= 6), the
/// unit itself for whole numbers.
fn step(values: impl Iterator<Item = f64>) -> Option<f64> {
    let decimals = |v: f64| (0..=6).find(|&d| ((v * 10f64.powi(d)).round() - v * 10f64.powi(d)).abs() < 1e-6);
    let most = values.take(5000).map(|v| decimals(v).unwrap_or(6)).max()?;
    Some(10f64.powi(-most))
}

fn rms(v: [f64; 3]) -> f64 {
    (v.iter().map(|x| x * x).sum::<f64>() / 3.0).sqrt()
}

fn median(values: impl Iterator<Item = f64>) -> Option<f64> {
    let mut values: Vec<f64> = values.collect();
    values.sort_by(f64::total_cmp);
    values.get(values.len() / 2).copied()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stream::{AccelUnit, GyroUnit, StreamOptions};

    /// A still board's log at 100 Hz (millis), in g and deg/s, without the samples numbered in `lost`;
    /// its gyro printed with one decimal and steady, its accelerometer with four.
    fn still_log(lost: &[usize]) -> StreamLog {
        let mut text = "millis,ax,ay,az,gx,gy,gz\n".to_owned();
        for i in (0..1000).filter(|i| !lost.contains(i)) {
            let wobble = [0.0, 0.003, -0.003, 0.0][i % 4];
            text += &format!("{},{wobble:.4},{:.4},{:.4},0.5,-0.2,0.1\n", i * 10, -wobble, 1.0 + wobble);
        }
        let options =
            StreamOptions { accel_unit: Some(AccelUnit::G), gyro_unit: Some(GyroUnit::DegPerS), ..Default::default() };
        StreamLog::parse(&text, &options).unwrap()
    }

    // NOTE: 4 mg at 100 Hz: a band of (4 mg / 400 ug/sqrt(Hz))^2 = 100 Hz; a mean to 0.1 mg takes
    // (4 / 0.1)^2 / 100 Hz = 16 s here, (0.4 / 0.1)^2 / 2 = 8 s behind the low-pass, 44 Hz being the
    // widest setting at or below the 50 Hz Nyquist frequency.
    #[test]
    fn a_stream_s_aliasing_cost_names_its_band_and_both_capture_times() {
        let words = aliasing(&still_log(&[]), 0.004).unwrap().words;
        for said in [
            "each sample scatters 4.0 mg",
            "about 100 Hz wide at 100 Hz",
            "takes 16 s here, 8 s with the chip's low-pass at 44 Hz",
        ] {
            assert!(words.contains(said), "no `{said}` in: {words}");
        }
    }

    #[test]
    fn a_gyro_printed_in_tenths_is_known_to_half_a_tenth() {
        let log = still_log(&[]);
        let still = Segment {
            first: 0,
            last: log.samples.len() - 1,
            samples: log.samples.len(),
            mean_g: [0.0, 0.0, 1.0],
            std_g: [0.002; 3],
            gyro_mean_dps: None,
        };
        let words = gyro_decimals(&log, &[still]).unwrap().words;
        let said = "step by 0.10 deg/s, more than its noise (0.000 deg/s): its bias is known no better than 0.05 deg/s";
        assert!(words.contains(said), "{words}");
    }

    #[test]
    fn the_samples_lost_in_gaps_are_counted_in_the_cost_line() {
        let lost = timestamps(&still_log(&[500, 700, 701, 702])).unwrap();
        assert_eq!((lost.kind, lost.words.as_str()), ("lost", "the timestamps show 4 samples lost in gaps"));
    }
}
