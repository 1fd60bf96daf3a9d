//! Noise characterisation of a still recording: the analysis is the core's
//! ([`accelcal_core::noise`], re-exported here); this module reads the recording's file (a
//! sketch's stream log is read by `stream::noise_input`) and runs the six axes one thread each.

pub mod input;

pub use accelcal_core::noise::*;

/// Analyses the six axes, one thread each.
pub fn analyse(series: &RateSeries) -> NoiseReport {
    let axes = std::thread::scope(|scope| {
        let handles: Vec<_> = AXES
            .iter()
            .zip(&series.axes)
            .map(|(name, rate)| scope.spawn(move || analyse_axis(name, rate, series.rate_hz)))
            .collect();
        handles.into_iter().map(|h| h.join().unwrap_or_else(|panic| std::panic::resume_unwind(panic))).collect()
    });
    NoiseReport::of(series, axes)
}
