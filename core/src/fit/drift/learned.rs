//! A temperature model the board already learned (`accelcal thermal`), kept by a session: its
//! captures are corrected by it to the model's reference temperature and only the nine parameters
//! are fitted to them, so the model's slopes, measured over tens of degrees, are not replaced by the
//! few tenths of a degree a one-minute session sees.

use shared::calibration::TemperatureModel;
use shared::Calibration;

use crate::data::{Dataset, Row};

/// Whether `model` was learned by `accelcal thermal` rather than fitted by a session, which fits a
/// first-order offset drift alone: a learned model has scale or gyro terms, or a higher order.
pub fn is_learned(model: &TemperatureModel) -> bool {
    let any = |k: &[[f32; 3]]| k.iter().flatten().any(|v| *v != 0.0);
    any(&model.scale) || any(&model.gyro_bias_dps) || any(&model.offset_g[1..])
}

/// The board calibration whose temperature model a session keeps, when it has a learned one.
pub fn kept(active: Option<Calibration>) -> Option<Calibration> {
    active.filter(|c| c.temperature.as_ref().is_some_and(is_learned))
}

/// The captures (in g and deg/s, with their temperatures) as the sensor would read them at the
/// learned model's reference temperature: m_ref = diag(1 + d(T))^-1 (m - o(T)) + o and
/// w_ref = w - (b(T) - b), with `learned`'s o and b standing for the sensor's own (their error
/// enters only through d(T), about 1e-4 per degC, times the difference).
pub fn at_reference(captures: &Dataset, learned: &Calibration) -> Dataset {
    let correct = |row: &Row| {
        let Some(temp_c) = row.temp_c.map(|t| t as f32) else { return row.clone() };
        let Some((offset_at, scale_at)) = learned.accel_terms_at(temp_c) else { return row.clone() };
        let reading = [0, 1, 2].map(|k| {
            let own = f64::from(learned.offset_g[k]);
            (row.reading[k] - f64::from(offset_at[k])) / (1.0 + f64::from(scale_at[k])) + own
        });
        let bias_change = shared::linalg::sub(learned.gyro_bias_at(temp_c), learned.gyro.bias_dps);
        let gyro_mean_dps = row.gyro_mean_dps.map(|w| [0, 1, 2].map(|k| w[k] - f64::from(bias_change[k])));
        Row { reading, gyro_mean_dps, ..row.clone() }
    };
    Dataset { rows: captures.rows.iter().map(correct).collect() }
}

#[cfg(test)]
mod tests {
    use shared::calibration::AccelRange;

    use super::*;

    /// A learned model around 25 degC: offset drift, sensitivity drift and gyro bias drift.
    fn learned() -> Calibration {
        let mut model = TemperatureModel::flat(25.0);
        model.offset_g[0] = [1e-3, -0.7e-3, 1.4e-3];
        model.scale[0] = [1.2e-4, -0.8e-4, 1.6e-4];
        model.gyro_bias_dps[0] = [0.05, -0.07, 0.04];
        let identity = Calibration::identity(AccelRange::G2);
        let gyro = shared::calibration::GyroCalibration { bias_dps: [0.5, -0.2, 0.1], ..identity.gyro };
        Calibration { offset_g: [0.02, -0.01, 0.05], gyro, temperature: Some(model), ..identity }
    }

    #[test]
    fn a_session_drift_is_not_learned_and_a_thermal_model_is() {
        let mut session_drift = TemperatureModel::flat(22.0);
        session_drift.offset_g[0] = [1e-3, 0.0, 0.0];
        assert!(!is_learned(&session_drift));
        assert!(is_learned(learned().temperature.as_ref().unwrap()));
        assert_eq!(kept(Some(Calibration { temperature: Some(session_drift), ..learned() })), None);
        assert_eq!(kept(None), None);
        assert!(kept(Some(learned())).is_some());
    }

    #[test]
    fn a_capture_at_another_temperature_is_moved_to_what_the_sensor_reads_at_the_reference() {
        // The sensor's raw reading of a = (0, 0, 1) g at 21 degC under the learned model: M^-1 = I,
        // m = diag(1 + d dT) a + o + c dT, dT = -4; the gyro reads b + e dT at rest.
        let calibration = learned();
        let dt = -4.0;
        let reading = [0.02 - 4e-3, -0.01 + 2.8e-3, (1.0 + 1.6e-4 * dt) + 0.05 - 5.6e-3];
        let gyro = [0.5 - 0.2, -0.2 + 0.28, 0.1 - 0.16];
        let row = Row { reading, temp_c: Some(21.0), gyro_mean_dps: Some(gyro), ..Row::default() };
        let moved = at_reference(&Dataset { rows: vec![row] }, &calibration).rows[0].clone();
        let wanted = [0.02, -0.01, 1.05];
        (0..3).for_each(|k| assert!((moved.reading[k] - wanted[k]).abs() < 1e-6, "{:?}", moved.reading));
        let bias = [0.5, -0.2, 0.1];
        (0..3).for_each(|k| assert!((moved.gyro_mean_dps.unwrap()[k] - bias[k]).abs() < 1e-5, "{moved:?}"));
    }
}
