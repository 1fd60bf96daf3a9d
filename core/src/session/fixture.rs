//! Captures made up for tests: one place that fills in a still capture's statistics.

use shared::protocol::CaptureStats;
use shared::AccelRange;

use super::CaptureRecord;
use crate::orientation::Orientation;

impl CaptureRecord {
    /// A still capture at `target` at 100 Hz and +-2 g: `samples` whose mean is `mean_g` and whose
    /// per-axis scatter is `std_g` (g), at die temperature `temp_c`, the gyro at rest.
    pub fn still(target: &Orientation, mean_g: [f64; 3], std_g: f32, samples: u32, temp_c: f64) -> Self {
        let stats = CaptureStats {
            samples,
            seconds: samples as f32 / 100.0,
            mean_g: mean_g.map(|v| v as f32),
            std_g: [std_g; 3],
            gyro_mean_dps: [0.0; 3],
            gyro_std_dps: [0.05; 3],
            temp_c: temp_c as f32,
            clipped: 0,
            range: AccelRange::G2,
        };
        // NOTE: a fixed time (2025-11-24): what these captures feed reads no clock.
        CaptureRecord::at(&target.name, Some(target.clone()), None, stats, 1_764_000_000.0)
    }
}
