//! Autopilot parameter files: ArduPilot `.param` and PX4 `.params` (QGroundControl's form). Both apply
//! per-axis offsets and scales, (m - o) .* s in m/s^2, and keep a gyro offset in rad/s; both carry the
//! temperature model's offset and gyro-bias terms.

use shared::calibration::{limits, TempCoefficients, TemperatureModel};
use shared::linalg::Vec3;
use shared::STANDARD_GRAVITY;

use super::loss::{best_diagonal, diagonal, loss, Carried};
use super::statement::{lines, Said};
use super::{text, Export, Source, HASH};

/// Radians per degree.
const RAD_PER_DEG: f64 = std::f64::consts::PI / 180.0;
/// ArduPilot's fixed TCAL reference temperature and coefficient scale (AP_InertialSensor_tempcal.cpp:
/// TEMP_REFERENCE 35, SCALE_FACTOR 1e6).
const ARDUPILOT_TCAL_REF_C: f64 = 35.0;
const ARDUPILOT_TCAL_SCALE: f64 = 1e6;

/// What both autopilots keep: offsets and the best diagonal scale, rounded to f32 as stored; the gyro offset.
pub struct Diagonal {
    /// What the values apply, in accelcal's units.
    pub carried: Carried,
    /// The per-axis scale, offset (m/s^2) and gyro offset (rad/s), as written.
    pub per_axis: [Vec3<f32>; 3],
}

/// The values both autopilots take.
pub fn diagonal_carried(source: &Source) -> Diagonal {
    let full = source.full();
    let scale = best_diagonal(&full.matrix).map(|v| v as f32);
    let offset_ms2 = full.offset_g.map(|v| (v * STANDARD_GRAVITY) as f32);
    let gyro_rad = source.gyro_bias_dps().map(|v| (v * RAD_PER_DEG) as f32);
    let carried = Carried {
        matrix: diagonal(scale.map(f64::from)),
        offset_g: offset_ms2.map(|v| f64::from(v) / STANDARD_GRAVITY),
        gyro_matrix: diagonal([1.0; 3]),
        gyro_bias_dps: Some(gyro_rad.map(|v| f64::from(v) / RAD_PER_DEG)),
    };
    Diagonal { carried, per_axis: [offset_ms2, scale, gyro_rad] }
}

/// NAME, VALUE for the offset, scale and gyro offset of each axis; `#` in a name is the axis.
fn per_axis(values: &[Vec3<f32>; 3], names: [&str; 3]) -> Vec<(String, String)> {
    let mut params = Vec::new();
    for (axis, letter) in ["X", "Y", "Z"].iter().enumerate() {
        for (name, value) in names.iter().zip(values) {
            params.push((name.replace('#', letter), value[axis].to_string()));
        }
    }
    params
}

/// What an autopilot says of itself; `carried_model` says what it does with a temperature model, if any.
fn said<'a>(title: &'a str, convention: &'a [&'a str], source: &Source, carried_model: &'a str) -> Said<'a> {
    Said {
        title,
        convention,
        carries: "accelerometer offsets and a scale per axis (no cross-axis terms); gyro offsets (no gyro scale)",
        temperature: if source.calibration.temperature.is_some() { carried_model } else { "none to carry" },
        lossy: true,
    }
}

const ARDUPILOT_CONVENTION: &[&str] = &[
    "ArduPilot: a = (m - INS_ACCOFFS) .* INS_ACCSCAL per axis, in m/s^2, offsets first (AP_InertialSensor_Backend.cpp)",
    "the off-diagonal terms of M (cross-axis and misalignment) have no parameter: the scale is the per-axis least-squares best",
    "gyro: w = w_raw - INS_GYROFFS in rad/s; ArduPilot measures it again at each boot unless INS_GYRO_CAL is 0",
    "TCAL: ArduPilot subtracts poly(T - 35) - poly(INS_ACC1_CALTEMP - 35) from the reading, poly(t) = (c1 + c2 t + c3 t^2) t / 1e6",
];

/// The ArduPilot parameter file (NAME,VALUE lines).
pub fn ardupilot(source: &Source) -> Export {
    let values = diagonal_carried(source);
    let loss = loss(&source.full(), &values.carried);
    let said = said(
        "ArduPilot (.param)",
        ARDUPILOT_CONVENTION,
        source,
        "TCAL carries the offset and gyro-bias terms (not a sensitivity drift)",
    );
    let mut params = per_axis(&values.per_axis, ["INS_ACCOFFS_#", "INS_ACCSCAL_#", "INS_GYROFFS_#"]);
    if let Some(model) = &source.calibration.temperature {
        params.extend(ardupilot_tcal(model, tcal_span_c(source)));
    }
    text(lines(source, &said, &loss), &HASH, &name_value_lines(&params), loss)
}

/// The die temperatures an autopilot applies the model between (TMIN, TMAX): those it was learned
/// over where what it came from records them, else the sensor's operating range (with ArduPilot's
/// TMAX limit of 80 degC).
// NOTE: outside them both autopilots hold the correction at the nearer edge (ArduPilot
// AP_InertialSensor_tempcal.cpp, TCal::correct_sensor; PX4 TemperatureCompensation::
// calc_thermal_offsets_3D), so a drift learned over a degree or two is not carried further.
pub fn tcal_span_c(source: &Source) -> (f32, f32) {
    let (low, high) = source.readings.drift_span_c.map_or(limits::OPERATING_TEMP_C, |(l, h)| (l as f32, h as f32));
    (low, high.min(80.0))
}

/// The parameters as NAME,VALUE lines (names and numbers need no quoting).
fn name_value_lines(params: &[(String, String)]) -> String {
    crate::data::csv_text(params.iter().map(|(name, value)| vec![name.clone(), value.clone()]))
}

/// INS_TCAL1_*: the model's offset and gyro-bias polynomials re-expanded about ArduPilot's 35 degC, with
/// the calibration temperature T_ref (where o(T_ref) = o).
fn ardupilot_tcal(model: &TemperatureModel, (low, high): (f32, f32)) -> Vec<(String, String)> {
    let t_ref = f64::from(model.ref_temp_c);
    let mut params = vec![
        ("INS_TCAL1_ENABLE".to_owned(), "1".to_owned()),
        ("INS_TCAL1_TMIN".to_owned(), low.to_string()),
        ("INS_TCAL1_TMAX".to_owned(), high.to_string()),
        ("INS_ACC1_CALTEMP".to_owned(), model.ref_temp_c.to_string()),
        ("INS_GYR1_CALTEMP".to_owned(), model.ref_temp_c.to_string()),
    ];
    let shift = mutant!("ardupilot-tcal-shift-sign", ARDUPILOT_TCAL_REF_C - t_ref, t_ref - ARDUPILOT_TCAL_REF_C);
    let accel =
        shifted(&model.offset_g, shift, mutant!("ardupilot-tcal-in-g", STANDARD_GRAVITY, 1.0) * ARDUPILOT_TCAL_SCALE);
    let gyro = shifted(&model.gyro_bias_dps, shift, RAD_PER_DEG * ARDUPILOT_TCAL_SCALE);
    for (k, (a, g)) in accel.iter().zip(&gyro).enumerate() {
        for (axis, name) in ["X", "Y", "Z"].iter().enumerate() {
            params.push((format!("INS_TCAL1_ACC{}_{name}", k + 1), (a[axis] as f32).to_string()));
            params.push((format!("INS_TCAL1_GYR{}_{name}", k + 1), (g[axis] as f32).to_string()));
        }
    }
    params
}

/// The coefficients of sum_k c_k (t + d)^k as a polynomial in t (orders 1-3; the constant drops out,
/// as ArduPilot takes a difference), times `factor`.
pub fn shifted(coefficients: &TempCoefficients, d: f64, factor: f64) -> [Vec3<f64>; 3] {
    let c = |k: usize| coefficients.get(k).map_or([0.0; 3], |v| v.map(f64::from));
    let (c1, c2, c3) = (c(0), c(1), c(2));
    [
        [0, 1, 2].map(|i| (c1[i] + 2.0 * c2[i] * d + 3.0 * c3[i] * d * d) * factor),
        [0, 1, 2].map(|i| (c2[i] + 3.0 * c3[i] * d) * factor),
        [0, 1, 2].map(|i| c3[i] * factor),
    ]
}

const PX4_CONVENTION: &[&str] = &[
    "PX4: a = (m - CAL_ACC0_xOFF - thermal offset) .* CAL_ACC0_xSCALE per axis, in m/s^2 (lib/sensor_calibration/Accelerometer.hpp)",
    "the off-diagonal terms of M (cross-axis and misalignment) have no parameter: the scale is the per-axis least-squares best",
    "gyro: w = w_raw - CAL_GYRO0_xOFF in rad/s",
    "TC_A0 / TC_G0: thermal offset = X0 + X1 dT + X2 dT^2 + X3 dT^3, dT = T - TREF (X0 = 0: CAL_ACC0 holds the offset at TREF)",
    "PX4 uses these only beside CAL_ACC0_ID / CAL_GYRO0_ID (and TC_A0_ID / TC_G0_ID) of your sensor: add them from QGroundControl",
];

/// The PX4 parameter file in QGroundControl's tab-separated form (vehicle, component, name, value, type).
pub fn px4(source: &Source) -> Export {
    let values = diagonal_carried(source);
    let loss = loss(&source.full(), &values.carried);
    let said = said(
        "PX4 (.params, QGroundControl)",
        PX4_CONVENTION,
        source,
        "TC_A0 and TC_G0 carry the offset and gyro-bias terms (not a sensitivity drift)",
    );
    let names = ["CAL_ACC0_#OFF", "CAL_ACC0_#SCALE", "CAL_GYRO0_#OFF"];
    let mut params: Vec<_> = per_axis(&values.per_axis, names).into_iter().map(|(n, v)| (n, v, REAL32)).collect();
    if let Some(model) = &source.calibration.temperature {
        params.extend(px4_thermal(model, tcal_span_c(source)));
    }
    let mut body = "# Vehicle-Id\tComponent-Id\tName\tValue\tType\n".to_owned();
    body.extend(params.iter().map(|(name, value, kind)| format!("1\t1\t{name}\t{value}\t{kind}\n")));
    text(lines(source, &said, &loss), &HASH, &body, loss)
}

/// MAVLink's MAV_PARAM_TYPE_REAL32 and MAV_PARAM_TYPE_INT32, QGroundControl's last column.
const REAL32: u8 = 9;
const INT32: u8 = 6;

/// TC_A_ENABLE, TC_A0_* and TC_G_ENABLE, TC_G0_*: the model about its own T_ref.
fn px4_thermal(model: &TemperatureModel, (low, high): (f32, f32)) -> Vec<(String, String, u8)> {
    let mut params = Vec::new();
    for (sensor, coefficients, factor) in [
        ("A", &model.offset_g, STANDARD_GRAVITY),
        ("G", &model.gyro_bias_dps, mutant!("px4-tc-gyro-in-deg", RAD_PER_DEG, 1.0)),
    ] {
        params.push((format!("TC_{sensor}_ENABLE"), "1".to_owned(), INT32));
        params.push((format!("TC_{sensor}0_TREF"), model.ref_temp_c.to_string(), REAL32));
        params.push((format!("TC_{sensor}0_TMIN"), low.to_string(), REAL32));
        params.push((format!("TC_{sensor}0_TMAX"), high.to_string(), REAL32));
        for order in 0..=3 {
            for axis in 0..3 {
                let value = if order == 0 {
                    0.0
                } else {
                    coefficients
                        .get(mutant!("px4-tc-order-shifted", order - 1, order))
                        .map_or(0.0, |c| f64::from(c[axis]))
                };
                params.push((format!("TC_{sensor}0_X{order}_{axis}"), ((value * factor) as f32).to_string(), REAL32));
            }
        }
    }
    params
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::export::{export, Target};

    /// The value of `name` in an exported parameter file (NAME,VALUE or QGroundControl's tab form).
    fn value_of(text: &str, name: &str) -> Option<f32> {
        let line = text.lines().find(|l| l.split([',', '\t']).any(|field| field == name))?;
        line.split([',', '\t']).skip_while(|field| *field != name).nth(1)?.parse().ok()
    }

    #[test]
    fn the_autopilots_apply_a_session_s_drift_only_over_the_temperatures_it_was_learned_over() {
        let session = crate::sim::sessions::adaptive(1, 1.4, 2.8e-3);
        let temps: Vec<f32> = session.captures.iter().map(|c| c.stats.temp_c).collect();
        let (low, high) = temps.iter().fold((f32::MAX, f32::MIN), |(l, h), t| (l.min(*t), h.max(*t)));
        let source = Source::from_session(&session, "s.json").unwrap();
        assert!(source.calibration.temperature.is_some(), "the warming session fitted no drift");
        let text = |target| String::from_utf8(export(&source, target).unwrap().bytes).unwrap();
        let (ardupilot, px4) = (text(Target::Ardupilot), text(Target::Px4));
        for (file, name) in [(&ardupilot, "INS_TCAL1_TMIN"), (&px4, "TC_A0_TMIN"), (&px4, "TC_G0_TMIN")] {
            assert!((value_of(file, name).unwrap() - low).abs() < 1e-3, "{name} against {low}: {file}");
        }
        for (file, name) in [(&ardupilot, "INS_TCAL1_TMAX"), (&px4, "TC_A0_TMAX"), (&px4, "TC_G0_TMAX")] {
            assert!((value_of(file, name).unwrap() - high).abs() < 1e-3, "{name} against {high}: {file}");
        }
        assert!(ardupilot.contains(&format!("learned over: {low:.1} to {high:.1} degC")), "{ardupilot}");
    }

    /// A model with every order of offset and gyro-bias drift, about 28.5 degC.
    fn every_order() -> TemperatureModel {
        TemperatureModel {
            offset_g: [[2e-4, -1e-4, 5e-5], [3e-6, -2e-6, 1e-6], [4e-8, 1e-8, -2e-8]],
            gyro_bias_dps: [[0.01, -0.02, 0.005], [2e-4, 1e-4, -3e-4], [5e-6, -1e-6, 2e-6]],
            ..TemperatureModel::flat(28.5)
        }
    }

    /// sum_k c_k (T - T_ref)^k of one axis, times `factor`: the model's change from T_ref to `temp_c`.
    fn drift_from_ref(coefficients: &TempCoefficients, axis: usize, temp_c: f64, factor: f64) -> f64 {
        let dt = temp_c - 28.5;
        coefficients.iter().enumerate().map(|(k, c)| f64::from(c[axis]) * dt.powi(k as i32 + 1)).sum::<f64>() * factor
    }

    /// The parameter file of a session's calibration carrying `every_order`.
    fn exported(target: Target) -> String {
        let mut source = crate::export::example_source();
        source.calibration.temperature = Some(every_order());
        String::from_utf8(export(&source, target).unwrap().bytes).unwrap()
    }

    // NOTE: what ArduPilot subtracts (AP_InertialSensor_tempcal.cpp, TCal::correct_sensor):
    // poly(T - 35) - poly(CALTEMP - 35), poly(t) = (c1 + c2 t + c3 t^2) t / 1e6, in m/s^2 and rad/s.
    #[test]
    fn ardupilot_s_tcal_takes_out_the_model_s_drift_in_m_s2_and_rad_s_at_every_temperature() {
        let file = exported(Target::Ardupilot);
        let poly = |sensor: &str, axis: &str, t: f64| {
            let c = |k: u8| f64::from(value_of(&file, &format!("INS_TCAL1_{sensor}{k}_{axis}")).unwrap());
            (c(1) + c(2) * t + c(3) * t * t) * t / 1e6
        };
        let cal_temp = f64::from(value_of(&file, "INS_ACC1_CALTEMP").unwrap());
        let model = every_order();
        for temp_c in [15.0, 35.0, 47.0] {
            for (axis, name) in ["X", "Y", "Z"].iter().enumerate() {
                let subtracted = |sensor| poly(sensor, name, temp_c - 35.0) - poly(sensor, name, cal_temp - 35.0);
                let accel = drift_from_ref(&model.offset_g, axis, temp_c, STANDARD_GRAVITY);
                let gyro = drift_from_ref(&model.gyro_bias_dps, axis, temp_c, RAD_PER_DEG);
                assert!(
                    (subtracted("ACC") - accel).abs() < 2e-6,
                    "{name} at {temp_c}: {} m/s^2 against {accel}",
                    subtracted("ACC")
                );
                assert!(
                    (subtracted("GYR") - gyro).abs() < 2e-7,
                    "{name} at {temp_c}: {} rad/s against {gyro}",
                    subtracted("GYR")
                );
            }
        }
    }

    // NOTE: PX4's thermal offset (TemperatureCompensation::calc_thermal_offsets_3D):
    // X0 + X1 dT + X2 dT^2 + X3 dT^3, dT = T - TREF, in m/s^2 and rad/s.
    #[test]
    fn px4_s_thermal_offsets_are_the_model_s_drift_in_m_s2_and_rad_s_at_every_temperature() {
        let file = exported(Target::Px4);
        let model = every_order();
        for temp_c in [15.0, 35.0, 47.0] {
            for axis in 0..3 {
                let offset = |sensor: &str| {
                    let dt = temp_c - f64::from(value_of(&file, &format!("TC_{sensor}0_TREF")).unwrap());
                    let x = |k: i32| f64::from(value_of(&file, &format!("TC_{sensor}0_X{k}_{axis}")).unwrap());
                    (0..=3).map(|k| x(k) * dt.powi(k)).sum::<f64>()
                };
                let accel = drift_from_ref(&model.offset_g, axis, temp_c, STANDARD_GRAVITY);
                let gyro = drift_from_ref(&model.gyro_bias_dps, axis, temp_c, RAD_PER_DEG);
                assert!(
                    (offset("A") - accel).abs() < 2e-6,
                    "axis {axis} at {temp_c}: {} m/s^2 against {accel}",
                    offset("A")
                );
                assert!(
                    (offset("G") - gyro).abs() < 2e-7,
                    "axis {axis} at {temp_c}: {} rad/s against {gyro}",
                    offset("G")
                );
            }
        }
    }

    #[test]
    fn a_model_whose_span_is_not_recorded_is_applied_over_the_operating_range_and_says_so() {
        let session = crate::sim::sessions::adaptive(1, 1.4, 2.8e-3);
        let mut source = Source::from_session(&session, "s.json").unwrap();
        source.readings.drift_span_c = None;
        let ardupilot = String::from_utf8(export(&source, Target::Ardupilot).unwrap().bytes).unwrap();
        let (low, high) = limits::OPERATING_TEMP_C;
        assert_eq!(value_of(&ardupilot, "INS_TCAL1_TMIN"), Some(low));
        assert_eq!(value_of(&ardupilot, "INS_TCAL1_TMAX"), Some(high.min(80.0)));
        assert!(ardupilot.contains("learned over: not recorded"), "{ardupilot}");
    }
}
