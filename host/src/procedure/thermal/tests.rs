//! Bins, span and stall rules of the learning run.

use shared::protocol::CaptureStats;
use shared::AccelRange;

use super::{stalled, ThermalBins};
use crate::procedure::ProcedureError;

fn stats(temp_c: f32, z_g: f32) -> CaptureStats {
    CaptureStats {
        samples: 500,
        seconds: 5.0,
        mean_g: [0.0, 0.0, z_g],
        std_g: [0.003; 3],
        gyro_mean_dps: [0.1, 0.2, 0.3],
        gyro_std_dps: [0.05; 3],
        temp_c,
        clipped: 0,
        range: AccelRange::G2,
    }
}

#[test]
fn captures_in_one_degree_and_one_orientation_share_a_bin_and_average() {
    let mut bins = ThermalBins::default();
    bins.add(0, [0.0, 0.0, 1.0], &stats(20.2, 1.0));
    bins.add(0, [0.0, 0.0, 1.0], &stats(20.8, 1.002));
    bins.add(1, [0.0, 0.0, -1.0], &stats(20.5, -1.0));
    bins.add(0, [0.0, 0.0, 1.0], &stats(21.1, 1.004));
    assert_eq!(bins.len(), 3);
    let first = bins.points()[0];
    assert!((first.temp_c - 20.5).abs() < 1e-5 && (first.accel_g[2] - 1.001).abs() < 1e-6, "{first:?}");
    assert!((bins.span_c() - 0.9).abs() < 1e-5);
}

#[test]
fn a_span_under_10_degc_is_refused_with_the_span_and_what_to_do() {
    let mut bins = ThermalBins::default();
    bins.add(0, [0.0, 0.0, 1.0], &stats(24.0, 1.0));
    bins.add(0, [0.0, 0.0, 1.0], &stats(33.5, 1.0));
    let error = bins.check_span().unwrap_err();
    assert!(matches!(error, ProcedureError::SpanTooSmall { .. }), "{error:?}");
    let text = error.to_string();
    assert!(text.contains("spanned only 9.5 degC (24.0 to 33.5 degC)") && text.contains("at least 10 degC"), "{text}");
    assert!(text.contains("let it warm"), "{text}");
    bins.add(0, [0.0, 0.0, 1.0], &stats(34.1, 1.0));
    assert!(bins.check_span().is_ok(), "10.1 degC is enough");
}

#[test]
fn a_temperature_that_stops_moving_is_a_stall() {
    let warming: Vec<f64> = (0..12).map(|i| 20.0 + 0.1 * f64::from(i)).collect();
    assert!(!stalled(&warming), "1.1 degC over 10 rounds is still warming");
    let settled: Vec<f64> = (0..12).map(|i| 30.0 + 0.02 * f64::from(i)).collect();
    assert!(stalled(&settled));
    assert!(!stalled(&settled[..9]), "fewer rounds than the window cannot be judged");
}
