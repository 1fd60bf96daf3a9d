//! The temperature fit on synthetic readings from a known model.

use shared::calibration::TemperatureModel;
use shared::{AccelRange, Calibration};

use super::{fit_temperature, ThermalFitError, ThermalPoint, ThermalReference};

fn reference(calibration: &Calibration) -> ThermalReference {
    ThermalReference { ref_temp_c: calibration.mean_temp_c, matrix: calibration.matrix }
}

const FACES: [[f64; 3]; 6] =
    [[1.0, 0.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, 1.0], [0.0, 0.0, -1.0]];

/// The static calibration at 25 degC and a true model with curvature.
fn truth() -> (Calibration, TemperatureModel) {
    let calibration = Calibration {
        matrix: [[1.0, 0.0, 0.0], [0.0, 0.99, 0.0], [0.0, 0.0, 1.02]],
        offset_g: [0.02, -0.01, 0.05],
        gyro: shared::calibration::GyroCalibration { bias_dps: [1.0, -0.5, 0.2], ..Default::default() },
        mean_temp_c: 25.0,
        ..Calibration::identity(AccelRange::G2)
    };
    let mut model = TemperatureModel::flat(25.0);
    model.offset_g = [[0.75e-3, -0.7e-3, 1.4e-3], [4e-6, 3e-6, -6e-6], [0.0; 3]];
    model.scale = [[1.2e-4, -0.8e-4, 1.6e-4], [0.0; 3], [0.0; 3]];
    model.gyro_bias_dps = [[0.05, -0.07, 0.04], [4e-4, -3e-4, 5e-4], [0.0; 3]];
    (calibration, model)
}

/// What the sensor reads at `temp_c` resting on `force`: m = (1 + d) M^-1 f + o(T), b(T) + 0.1 f.
fn reading(calibration: &Calibration, model: &TemperatureModel, temp_c: f64, force: [f64; 3]) -> ThermalPoint {
    let dt = temp_c - 25.0;
    let poly = |c: &[[f32; 3]; 3], k: usize| (0..3).map(|j| f64::from(c[j][k]) * dt.powi(j as i32 + 1)).sum::<f64>();
    let accel = [0, 1, 2].map(|k| {
        let explained = force[k] / f64::from(calibration.matrix[k][k]);
        (1.0 + poly(&model.scale, k)) * explained + f64::from(calibration.offset_g[k]) + poly(&model.offset_g, k)
    });
    let gyro =
        [0, 1, 2].map(|k| f64::from(calibration.gyro.bias_dps[k]) + poly(&model.gyro_bias_dps, k) + 0.1 * force[k]);
    ThermalPoint { temp_c, force_g: force, accel_g: accel, gyro_dps: gyro }
}

#[test]
fn six_faces_across_15_to_45_degc_recover_offset_scale_and_gyro_drift() {
    let (calibration, model) = truth();
    let points: Vec<ThermalPoint> =
        (0..31).flat_map(|t| FACES.map(|f| reading(&calibration, &model, 15.0 + f64::from(t) + 0.3, f))).collect();
    let fit = fit_temperature(&reference(&calibration), &points).unwrap();
    assert!(fit.scale_fitted);
    for axis in 0..3 {
        for k in 0..2 {
            let offset = fit.model.offset_g[k][axis] - model.offset_g[k][axis];
            assert!(offset.abs() < 1e-7, "c{} axis {axis}: off by {offset:e}", k + 1);
            let gyro = fit.model.gyro_bias_dps[k][axis] - model.gyro_bias_dps[k][axis];
            assert!(gyro.abs() < 1e-5, "e{} axis {axis}: off by {gyro:e}", k + 1);
        }
        let scale = fit.model.scale[0][axis] - model.scale[0][axis];
        assert!(scale.abs() < 1e-7, "d1 axis {axis}: off by {scale:e}");
    }
    assert!(fit.held_out_mg < 1e-3, "{}", fit.held_out_mg);
}

#[test]
fn one_orientation_gives_the_offset_drift_but_not_the_sensitivity() {
    let (calibration, model) = truth();
    let points: Vec<ThermalPoint> =
        (0..31).map(|t| reading(&calibration, &model, 15.0 + f64::from(t), [0.0, 0.0, 1.0])).collect();
    let fit = fit_temperature(&reference(&calibration), &points).unwrap();
    assert!(!fit.scale_fitted);
    assert_eq!(fit.model.scale, [[0.0; 3]; 3]);
    // x and y see no force: their offset drift is exact; z's absorbs its sensitivity drift (1.6e-4/degC x 1/1.02 g).
    assert!((fit.model.offset_g[0][0] - 0.75e-3).abs() < 1e-7, "{:?}", fit.model.offset_g);
    assert!((fit.model.offset_g[0][2] - (1.4e-3 + 1.6e-4 / 1.02)).abs() < 1e-6, "{:?}", fit.model.offset_g);
}

#[test]
fn fewer_than_six_temperature_bins_are_refused() {
    let (calibration, model) = truth();
    let points: Vec<ThermalPoint> =
        (0..5).map(|t| reading(&calibration, &model, 20.0 + f64::from(t), FACES[0])).collect();
    assert_eq!(fit_temperature(&reference(&calibration), &points), Err(ThermalFitError::TooFewBins { bins: 5 }));
}

/// Readings at the six faces at each of `temps`, with (accelerometer g, gyro deg/s) of white noise.
fn noisy_faces(
    calibration: &Calibration,
    model: &TemperatureModel,
    temps: &[f64],
    (accel_g, gyro_dps): (f64, f64),
    seed: u64,
) -> Vec<ThermalPoint> {
    use rand_distr::{Distribution, Normal};
    use rand_xoshiro::rand_core::SeedableRng;
    let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(seed);
    let mut normal = |sigma: f64| Normal::new(0.0, sigma).unwrap().sample(&mut rng);
    let mut points = Vec::new();
    for &temp_c in temps {
        for face in FACES {
            let mut p = reading(calibration, model, temp_c, face);
            p.accel_g = p.accel_g.map(|a| a + normal(accel_g));
            p.gyro_dps = p.gyro_dps.map(|w| w + normal(gyro_dps));
            points.push(p);
        }
    }
    points
}

#[test]
fn the_held_out_error_of_noisy_readings_is_their_noise_per_axis() {
    // Readings with 0.5 mg of independent noise on each axis: a model fitted to one half predicts the
    // other to the noise itself, times sqrt(1 + p / n) = 1.04 for up to 8 coefficients from 93 points.
    let (calibration, model) = truth();
    let temps: Vec<f64> = (0..31).map(|t| 15.0 + f64::from(t) + 0.3).collect();
    let points = noisy_faces(&calibration, &model, &temps, (0.5e-3, 0.0), 5);
    let fit = fit_temperature(&reference(&calibration), &points).unwrap();
    assert!((0.47..0.58).contains(&fit.held_out_mg), "held out {} mg for 0.5 mg of noise", fit.held_out_mg);
}

#[test]
fn a_short_warming_gets_no_higher_order_than_its_span_supports() {
    // A quick 16 degC warming (20 to 36 degC) with 0.1 mg of noise: its held-out error alone would
    // choose a higher order, which extrapolates to the ends of the operating range the chip applies
    // it over. One order per 10 degC: linear only.
    let (calibration, model) = truth();
    let temps: Vec<f64> = (0..17).map(|t| 20.0 + f64::from(t) * 0.97).collect();
    let points = noisy_faces(&calibration, &model, &temps, (0.1e-3, 1e-3), 23);
    let fit = fit_temperature(&reference(&calibration), &points).unwrap();
    assert_eq!((fit.accel_order, fit.gyro_order), ([1; 3], [1; 3]));
    let mut plausible = calibration;
    plausible.temperature = Some(fit.model);
    assert_eq!(plausible.validate(), Ok(()), "a first order from 16 degC holds over -40..85 degC");
    // Thirty degrees support a cubic: the quadratic truth over 15..45 degC still gets its second order.
    let wide: Vec<ThermalPoint> =
        (0..31).flat_map(|t| FACES.map(|f| reading(&calibration, &model, 15.0 + f64::from(t) + 0.3, f))).collect();
    assert!(fit_temperature(&reference(&calibration), &wide).unwrap().accel_order.iter().all(|&o| o >= 2));
}
