//! xio Fusion: FusionMatrix and FusionVector values for FusionCalibrationInertial, whose model is
//! calibrated = misalignment * ((uncalibrated - offset) .* sensitivity) (Fusion's FusionCalibration.h;
//! the Python package `imufusion` exposes the same as `model_inertial`). Fed raw counts: offset in
//! counts, sensitivity in g (deg/s) per count, misalignment = M (G); carries everything.

use super::code::{c_matrix, c_vector};
use super::loss::loss;
use super::statement::{lines, Said};
use super::{text, Export, Source, SLASHES};

const CONVENTION: &[&str] = &[
    "FusionCalibrationInertial: calibrated = misalignment * ((uncalibrated - offset) .* sensitivity)",
    "uncalibrated in raw counts; offset in counts; sensitivity in g per count (accelerometer), deg/s per count (gyro)",
    "misalignment = accelcal's M (G for the gyro), row-major as FusionMatrix stores it: xx, xy, xz, yx, ... (column vectors)",
    "the result is in g and deg/s, the units FusionAhrsUpdate takes",
];

const FUSION_SAID: Said = Said {
    title: "xio Fusion (FusionCalibrationInertial)",
    convention: CONVENTION,
    carries: "M, o, G, b in full (float32)",
    temperature: "not applied",
    lossy: false,
};

/// The Fusion values, as a C/C++ snippet that includes Fusion.h.
pub fn fusion(source: &Source) -> Export {
    let full = source.full();
    let loss = loss(&full, &full);
    let lsb = source.accel_per_g();
    // NOTE: FusionMatrix and FusionVector are unions whose first member is the float array (Fusion's
    // FusionMath.h): the array's own braces inside the union's keep gcc's -Wmissing-braces quiet in C.
    let flat =
        |m: &[[f64; 3]; 3]| format!("{{{}}}", c_matrix(m).replace("}, {", ", ").replace("{{", "{").replace("}}", "}"));
    let union = |v: &[f64; 3]| format!("{{{}}}", c_vector(v));
    let body = format!(
        "\n#include \"Fusion.h\"\n\n\
         static const FusionMatrix accelerometerMisalignment = {};\n\
         static const FusionVector accelerometerSensitivity = {};\n\
         static const FusionVector accelerometerOffset = {};\n\n\
         static const FusionMatrix gyroscopeMisalignment = {};\n\
         static const FusionVector gyroscopeSensitivity = {};\n\
         static const FusionVector gyroscopeOffset = {};\n",
        flat(&full.matrix),
        union(&[1.0 / lsb; 3]),
        union(&full.offset_g.map(|v| mutant!("fusion-offset-in-g", v * lsb, v))),
        flat(&full.gyro_matrix),
        union(&[1.0 / source.gyro_per_dps(); 3]),
        union(&source.gyro_bias_dps().map(|v| mutant!("fusion-gyro-offset-sign", v, -v) * source.gyro_per_dps())),
    );
    text(lines(source, &FUSION_SAID, &loss), &SLASHES, &body, loss)
}

#[cfg(test)]
mod tests {
    use super::super::{c_vector_of, example_source};
    use super::*;

    // NOTE: Fusion's FusionCalibrationInertial: calibrated = misalignment * ((uncalibrated - offset) .*
    // sensitivity), the uncalibrated reading in counts: both offsets are the bias in counts, not negated.
    #[test]
    fn fusion_s_offsets_are_the_biases_in_counts() {
        let source = example_source();
        let text = String::from_utf8(fusion(&source).bytes).unwrap();
        let (lsb_g, lsb_dps) = (source.accel_per_g(), source.gyro_per_dps());
        let accel = c_vector_of(&text, "accelerometerOffset").unwrap();
        let gyro = c_vector_of(&text, "gyroscopeOffset").unwrap();
        for axis in 0..3 {
            let wanted = source.full().offset_g[axis] * lsb_g;
            assert!((accel[axis] - wanted).abs() <= 1e-6 * wanted.abs().max(1.0), "{accel:?}: {text}");
            let wanted = source.gyro_bias_dps()[axis] * lsb_dps;
            assert!((gyro[axis] - wanted).abs() <= 1e-6 * wanted.abs(), "{gyro:?}: {text}");
        }
        assert!(source.full().offset_g.iter().all(|o| o.abs() * lsb_g > 10.0), "an offset too small to show");
    }
}
