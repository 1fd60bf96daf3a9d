//! The simulated sensor's truth as the report shows it: the report's truth types are plain numbers
//! (the core knows nothing of the simulator); this fills them in from the simulator's physics.

use firmware::sim::physics::TrueErrors;
use firmware::sim::thermal::ThermalDrift;

use crate::report::gyro::TruthGyroJson;
use crate::report::{DriftJson, TruthJson};

/// The truth `at` the temperature `temp_c` (TEMP_OUT), with the sensor's `drift` when it has one.
pub fn truth_json(temp_c: f32, at: &TrueErrors, drift: Option<DriftJson>) -> TruthJson {
    TruthJson { temp_c, matrix: at.matrix, offset: at.offset_g, gyro: truth_gyro_json(at), drift }
}

/// The true gyro correction at one temperature.
pub fn truth_gyro_json(truth: &TrueErrors) -> TruthGyroJson {
    TruthGyroJson { matrix: truth.gyro_matrix, bias_dps: truth.gyro_bias_dps }
}

/// The `drift` about the die temperature `ref_die_c`, where the truth is `reference`.
pub fn drift_json(reference: &TrueErrors, drift: &ThermalDrift, ref_die_c: f32, reading_offset_c: f32) -> DriftJson {
    DriftJson {
        reading_offset_c,
        ref_die_c,
        ref_matrix: reference.matrix,
        ref_offset: reference.offset_g,
        ref_gyro_bias_dps: reference.gyro_bias_dps,
        offset_g: drift.offset_g,
        scale: drift.scale,
        gyro_bias_dps: drift.gyro_bias_dps,
    }
}
