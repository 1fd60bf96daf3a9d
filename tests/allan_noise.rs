//! The noise analysis finds the noise terms put into a synthetic recording (white noise within 5 %,
//! bias instability within a factor 1.5), and its Allan deviation equals allantools' `oadev`.

use std::io::Write;
use std::process::{Command, Stdio};

use accelcal::noise::{self, allan};
use accelcal::sim::noise::{noisy_series, TrueNoise};

/// Sample rate of the synthetic recordings (the analysis does not depend on it; 100 Hz keeps the
/// unoptimised test build quick).
const RATE_HZ: f64 = 100.0;
/// Two hours: the longest averaging time analysed is a tenth of it, 720 s, well inside the flicker floor.
const SECONDS: f64 = 7200.0;

fn check_recovery(name: &'static str, truth: TrueNoise, mean: f64, seed: u64) {
    let series = noisy_series(&truth, mean, RATE_HZ, (RATE_HZ * SECONDS) as usize, seed);
    let axis = noise::analyse_axis(name, &series, RATE_HZ);
    let fitted = axis.terms.expect("a two-hour recording is fitted");
    let white = fitted.white_noise_density() / truth.white_noise_density;
    let bias = fitted.bias_instability / truth.bias_instability;
    println!(
        "{name}: white noise {white:.4} x truth, bias instability {bias:.3} x truth at {:.0} s",
        fitted.bias_instability_tau_s
    );
    assert!((white - 1.0).abs() < 0.05, "{name}: white noise density {white} x the truth");
    assert!((1.0 / 1.5..1.5).contains(&bias), "{name}: bias instability {bias} x the truth");
}

#[test]
fn accelerometer_white_noise_within_5_percent_and_bias_instability_within_1_5x_from_2_hours() {
    // 400 ug/sqrt(Hz) as the datasheet; 100 ug of bias instability and a slow random walk.
    let truth = TrueNoise { white_noise_density: 400e-6, bias_instability: 100e-6, random_walk: 1e-6 };
    check_recovery("accel_z", truth, 1.0, 11);
}

#[test]
fn gyro_white_noise_within_5_percent_and_bias_instability_within_1_5x_from_2_hours() {
    // 0.005 deg/s/sqrt(Hz) as the datasheet; 10 deg/h of bias instability.
    let truth = TrueNoise { white_noise_density: 0.005, bias_instability: 10.0 / 3600.0, random_walk: 1e-5 };
    check_recovery("gyro_x", truth, 0.3, 12);
}

/// allantools' `oadev` of one rate series at the given averaging factors, or why it could not run.
fn allantools_oadev(rate: &[f64], rate_hz: f64, factors: &[usize]) -> Result<Vec<(f64, f64)>, String> {
    let script = "import sys, json, numpy, allantools\n\
        d = json.load(sys.stdin)\n\
        t, a, e, n = allantools.oadev(numpy.array(d['y']), rate=d['rate'], data_type='freq', taus=numpy.array(d['taus']))\n\
        print(json.dumps({'taus': list(t), 'adev': list(a)}))\n";
    let taus: Vec<f64> = factors.iter().map(|&m| m as f64 / rate_hz).collect();
    let input = format!("{{\"y\": {:?}, \"rate\": {rate_hz:?}, \"taus\": {taus:?}}}", rate);
    let mut child = Command::new("python3")
        .args(["-c", script])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| format!("cannot run python3 ({e})"))?;
    child.stdin.take().ok_or("no stdin")?.write_all(input.as_bytes()).map_err(|e| e.to_string())?;
    let output = child.wait_with_output().map_err(|e| e.to_string())?;
    if !output.status.success() {
        return Err(format!(
            "python3 with numpy and allantools failed: {}",
            String::from_utf8_lossy(&output.stderr).trim()
        ));
    }
    parse_pairs(&String::from_utf8_lossy(&output.stdout))
}

fn parse_pairs(text: &str) -> Result<Vec<(f64, f64)>, String> {
    let numbers = |key: &str| -> Result<Vec<f64>, String> {
        let start = text.find(&format!("\"{key}\": [")).ok_or(format!("no {key} in {text}"))? + key.len() + 5;
        let end = start + text[start..].find(']').ok_or("unterminated list")?;
        text[start..end].split(',').map(|v| v.trim().parse::<f64>().map_err(|e| e.to_string())).collect()
    };
    Ok(numbers("taus")?.into_iter().zip(numbers("adev")?).collect())
}

#[test]
#[cfg_attr(
    not(has_allantools),
    ignore = "needs python3 with numpy and allantools (pip install allantools numpy); CI=true runs it"
)]
fn allan_deviation_equals_allantools_oadev_to_1e_9_relative() {
    let truth = TrueNoise { white_noise_density: 400e-6, bias_instability: 40e-6, random_walk: 4e-6 };
    let rate_hz = 1000.0;
    let series = noisy_series(&truth, 0.98, rate_hz, 20_000, 5);
    let factors = allan::averaging_factors(series.len(), 10);
    let ours = allan::overlapping_adev(&series, rate_hz, &factors);
    let theirs = allantools_oadev(&series, rate_hz, &factors).unwrap_or_else(|reason| {
        panic!("needs python3 with numpy and allantools (pip install allantools numpy): {reason}")
    });
    assert_eq!(ours.len(), theirs.len(), "allantools computed other averaging times: {theirs:?}");
    let mut worst = 0f64;
    for (point, (tau_s, adev)) in ours.iter().zip(&theirs) {
        assert!((point.tau_s - tau_s).abs() < 1e-12, "tau {} vs {tau_s}", point.tau_s);
        worst = worst.max((point.adev / adev - 1.0).abs());
    }
    println!("largest relative difference from allantools over {} averaging times: {worst:.2e}", ours.len());
    assert!(worst < 1e-9, "largest relative difference {worst:e}");
}
