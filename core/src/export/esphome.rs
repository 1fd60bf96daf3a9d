//! ESPHome: its `mpu6050` sensor platform reads the chip itself and does no calibration (ESPHome's
//! MPU6050 page). The export is a `sensor:` fragment in two forms: per-axis `filters` on the
//! platform's own sensors (a scale and an offset per axis), and `template` sensors whose `lambda`
//! applies what the per-axis form leaves, so that they carry the whole calibration.
//!
//! ESPHome's mpu6050.cpp sets the accelerometer to +-2 g and the gyro to +-2000 deg/s, and publishes
//! m/s^2 = raw * 0.000061 * 9.80665 and deg/s = raw * 0.060975 (its constants, not the datasheet's
//! 1/16384 and 1/16.4): the filters' factors undo those for the datasheet's sensitivities.

use shared::linalg::{Mat3, Vec3};
use shared::{AccelRange, GyroRange, STANDARD_GRAVITY};

use super::loss::{best_diagonal, diagonal, loss, Carried, Loss};
use super::statement::{lines, takes, Said};
use super::{float, text, Export, Source, HASH};

/// g per count ESPHome's mpu6050 publishes with at +-2 g (mpu6050.cpp, MPU6050_RANGE_PER_DIGIT_2G).
const ESPHOME_G_PER_COUNT: f64 = 0.000061;
/// deg/s per count ESPHome's mpu6050 publishes with at +-2000 deg/s (MPU6050_SCALE_DPS_PER_DIGIT_2000).
const ESPHOME_DPS_PER_COUNT: f64 = 0.060975;
/// The sensitivities of the ranges ESPHome sets (MPU-6050 Product Specification 6.1, 6.2).
const COUNTS_PER_G: f64 = AccelRange::G2.lsb_per_g() as f64;
const COUNTS_PER_DPS: f64 = GyroRange::Dps2000.lsb_per_dps();

const CONVENTION: &[&str] = &[
    "ESPHome's mpu6050 reads +-2 g and +-2000 deg/s and publishes m/s^2 = raw * 0.000061 * 9.80665, deg/s = raw * \
     0.060975 (its mpu6050.cpp)",
    "per-axis form, the filters on the mpu6050's own sensors: value * multiply + offset = g * s_i (m_i - o_i) in \
     m/s^2 (s_i w_i - s_i b_i in deg/s), m_i = raw / 16384 in g; multiply also undoes ESPHome's 0.000061 for 1/16384",
    "s_i is the per-axis scale that leaves least error over the sphere; it carries the offsets and that scale, not the \
     cross-axis terms",
    "whole form, the template sensors: their lambda multiplies the per-axis sensors' values by R = M diag(1/s) (R_g = G \
     diag(1/s_g) for the gyro), which gives M (m - o) in m/s^2 and G (w - b) in deg/s: the whole calibration",
    "the template sensors read the latest value of each axis: give them the mpu6050's update_interval",
];

/// The gyro's range here and where G was fitted.
const GYRO_RANGE_LINE: &str = "NOTE: ESPHome reads the gyro at +-2000 deg/s (0.061 deg/s a count); b is in deg/s \
                               whatever the range, G holds at the range it was fitted at";

/// The per-axis scales and what each form applies.
struct Forms {
    accel_scale: Vec3<f64>,
    gyro_scale: Vec3<f64>,
    per_axis: Carried,
}

fn forms(source: &Source) -> Forms {
    let full = source.full();
    let (accel_scale, gyro_scale) = (best_diagonal(&full.matrix), best_diagonal(&full.gyro_matrix));
    let per_axis = Carried { matrix: diagonal(accel_scale), gyro_matrix: diagonal(gyro_scale), ..full };
    Forms { accel_scale, gyro_scale, per_axis }
}

/// The YAML fragment.
pub fn esphome(source: &Source) -> Export {
    let full = source.full();
    let forms = forms(source);
    let (whole, per_axis) = (loss(&full, &full), loss(&full, &forms.per_axis));
    let said = Said {
        title: "ESPHome (mpu6050 sensor platform)",
        convention: CONVENTION,
        carries: "M, o, G, b in full through the template sensors (float32); the per-axis sensors alone carry the \
                  offsets, the gyro bias and a scale per axis",
        temperature: "ESPHome's mpu6050 has no temperature model: not carried",
        lossy: false,
    };
    // NOTE: ESPHome reads the chip itself: what the sketch or firmware it was calibrated through took
    // does not apply here.
    let takes = (takes(source), "what follows takes the values ESPHome's mpu6050 publishes (m/s^2, deg/s)");
    let mut statement: Vec<String> =
        lines(source, &said, &whole).iter().map(|l| l.replace(&takes.0, takes.1)).collect();
    statement.push(per_axis_line(&per_axis));
    statement.extend(range_line(source));
    statement.push(GYRO_RANGE_LINE.to_owned());
    text(statement, &HASH, &body(source, &forms), whole)
}

/// What the per-axis sensors alone lose, in the form the loss lines have.
fn per_axis_line(loss: &Loss) -> String {
    format!(
        "lost by the per-axis sensors alone (filters, no template): {:.4} mg rms, {:.4} mg worst; gyro {:.3} % rms, \
         {:.3} % worst",
        loss.rms_mg, loss.worst_mg, loss.gyro_rms_pct, loss.gyro_worst_pct
    )
}

/// A warning where the calibration was made at another accelerometer range than ESPHome's +-2 g.
fn range_line(source: &Source) -> Option<String> {
    let range = source.calibration.range;
    (range != AccelRange::G2).then(|| {
        format!(
            "NOTE: calibrated at +-{} g; ESPHome reads +-2 g, where the offsets and scales may differ: calibrate at \
             +-2 g for this node",
            range.full_scale_g()
        )
    })
}

/// The `sensor:` list: the platform with its filters, then the template sensors.
fn body(source: &Source, forms: &Forms) -> String {
    let full = source.full();
    let accel_multiply = forms.accel_scale.map(|s| s / (ESPHOME_G_PER_COUNT * COUNTS_PER_G));
    let accel_offset = [0, 1, 2].map(|i| -STANDARD_GRAVITY * forms.accel_scale[i] * full.offset_g[i]);
    let gyro_multiply = forms.gyro_scale.map(|s| s / (ESPHOME_DPS_PER_COUNT * COUNTS_PER_DPS));
    let bias = source.gyro_bias_dps();
    let gyro_offset = [0, 1, 2].map(|i| -forms.gyro_scale[i] * bias[i]);
    let mut out = "\nsensor:\n  - platform: mpu6050\n    address: 0x68\n".to_owned();
    for (i, axis) in ["x", "y", "z"].iter().enumerate() {
        out.push_str(&axis_sensor("accel", axis, accel_multiply[i], accel_offset[i]));
    }
    for (i, axis) in ["x", "y", "z"].iter().enumerate() {
        out.push_str(&axis_sensor("gyro", axis, gyro_multiply[i], gyro_offset[i]));
    }
    let accel_rest = rest(&full.matrix, &forms.accel_scale);
    let gyro_rest = rest(&full.gyro_matrix, &forms.gyro_scale);
    for (i, axis) in ["x", "y", "z"].iter().enumerate() {
        out.push_str(&template("accel", axis, &accel_rest[i], "m/s²"));
    }
    for (i, axis) in ["x", "y", "z"].iter().enumerate() {
        out.push_str(&template("gyro", axis, &gyro_rest[i], "°/s"));
    }
    out
}

/// R = matrix diag(1/scale): what the template sensors apply to the per-axis sensors' values.
fn rest(matrix: &Mat3<f64>, scale: &Vec3<f64>) -> Mat3<f64> {
    matrix.map(|row| [0, 1, 2].map(|j| row[j] / scale[j]))
}

/// One axis of the platform, with its filters.
fn axis_sensor(kind: &str, axis: &str, multiply: f64, offset: f64) -> String {
    format!(
        "    {kind}_{axis}:\n      name: \"MPU6050 {} {}\"\n      id: accelcal_{kind}_{axis}\n      filters:\n        \
         - multiply: {}\n        - offset: {}\n",
        title(kind),
        axis.to_uppercase(),
        multiply as f32,
        offset as f32
    )
}

/// One template sensor: row `row` of R over the three per-axis sensors.
fn template(kind: &str, axis: &str, row: &Vec3<f64>, unit: &str) -> String {
    let terms: Vec<String> = ["x", "y", "z"]
        .iter()
        .zip(row)
        .map(|(a, v)| format!("{}f * id(accelcal_{kind}_{a}).state", float(*v)))
        .collect();
    format!(
        "  - platform: template\n    name: \"MPU6050 {} {} calibrated\"\n    id: accelcal_{kind}_{axis}_calibrated\n    \
         unit_of_measurement: \"{unit}\"\n    accuracy_decimals: 4\n    lambda: |-\n      return {};\n",
        title(kind),
        axis.to_uppercase(),
        terms.join(" + ")
    )
}

fn title(kind: &str) -> &'static str {
    if kind == "accel" {
        "Accel"
    } else {
        "Gyro"
    }
}

#[cfg(test)]
mod tests {
    use super::super::example_source;
    use super::*;

    // NOTE: the template's R times the per-axis values s .* (m - o) is M (m - o): the whole calibration.
    #[test]
    fn the_template_rows_times_the_per_axis_values_give_the_whole_calibration() {
        let source = example_source();
        let (full, forms) = (source.full(), forms(&source));
        let rest = rest(&full.matrix, &forms.accel_scale);
        let m = [0.3, -0.2, 0.95];
        let per_axis = [0, 1, 2].map(|i| forms.accel_scale[i] * (m[i] - full.offset_g[i]));
        for (i, (rest_row, row)) in rest.iter().zip(&full.matrix).enumerate() {
            let via = (0..3).map(|j| rest_row[j] * per_axis[j]).sum::<f64>();
            let wanted = (0..3).map(|j| row[j] * (m[j] - full.offset_g[j])).sum::<f64>();
            assert!((via - wanted).abs() < 1e-12, "axis {i}: {via} against {wanted}");
        }
    }
}
