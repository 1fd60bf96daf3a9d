//! The corrections against hand-computed values, and each plausibility limit.

use super::*;

fn plausible() -> Calibration {
    Calibration {
        matrix: [[1.01, 0.002, -0.007], [0.0, 0.997, 0.0005], [0.0, 0.0, 1.017]],
        offset_g: [0.0276, -0.0057, -0.0783],
        gyro: GyroCalibration {
            matrix: [[1.02, 0.004, 0.0], [0.0, 0.98, 0.0], [0.0, -0.003, 1.0]],
            bias_dps: [-1.5, 0.8, 0.2],
        },
        temperature: Some(thermal()),
        ..Calibration::identity(AccelRange::G2)
    }
}

/// Within the datasheet's tempcos: 1 mg/degC offset, 0.02 %/degC scale, 0.05 deg/s/degC gyro bias.
fn thermal() -> TemperatureModel {
    TemperatureModel {
        offset_g: [[0.001, -0.0008, 0.002], [1e-5, 0.0, -2e-5], [0.0; 3]],
        scale: [[2e-4, -1e-4, 0.0], [0.0; 3], [0.0; 3]],
        gyro_bias_dps: [[0.05, -0.04, 0.09], [0.0; 3], [1e-6, 0.0, 0.0]],
        ..TemperatureModel::flat(25.0)
    }
}

fn close(a: Vec3<f32>, b: Vec3<f32>, tolerance: f32) -> bool {
    a.iter().zip(&b).all(|(x, y)| (x - y).abs() <= tolerance)
}

#[test]
fn apply_subtracts_offset_then_multiplies() {
    let cal = Calibration {
        matrix: [[2.0, 0.0, 0.0], [0.0, 1.0, 0.5], [0.0, 0.0, 1.0]],
        offset_g: [0.5, 0.0, 1.0],
        ..Calibration::identity(AccelRange::G2)
    };
    // m - o = (0.5, 1, 1); M (m - o) = (1.0, 1.5, 1.0)
    assert_eq!(cal.apply([1.0, 1.0, 2.0]), [1.0, 1.5, 1.0]);
    assert_eq!(cal.apply_at([1.0, 1.0, 2.0], 60.0), [1.0, 1.5, 1.0], "no model: the temperature changes nothing");
}

#[test]
fn apply_at_moves_offset_and_scale_with_the_temperature_difference() {
    let cal = Calibration {
        matrix: [[2.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        offset_g: [0.5, 0.0, 0.0],
        temperature: Some(TemperatureModel {
            offset_g: [[0.01, 0.0, 0.0], [0.001, 0.0, 0.0], [0.0; 3]],
            scale: [[0.0, 0.02, 0.0], [0.0; 3], [0.0, 0.0, 0.001]],
            ..TemperatureModel::flat(20.0)
        }),
        ..Calibration::identity(AccelRange::G2)
    };
    // dT = 10: o_x = 0.5 + 0.1 + 0.1 = 0.7; s_y = 1 + 0.2 = 1.2; s_z = 1 + 1 = 2.
    // a = (2 (1.7 - 0.7), 0.6 / 1.2, 3 / 2) = (2, 0.5, 1.5).
    assert!(
        close(cal.apply_at([1.7, 0.6, 3.0], 30.0), [2.0, 0.5, 1.5], 1e-6),
        "{:?}",
        cal.apply_at([1.7, 0.6, 3.0], 30.0)
    );
    // At T_ref the model vanishes: exactly the plain correction.
    assert_eq!(cal.apply_at([1.7, 0.6, 3.0], 20.0), cal.apply([1.7, 0.6, 3.0]));
    // A temperature beyond the operating range is held to its end, where the model was validated.
    let hottest = limits::OPERATING_TEMP_C.1;
    assert_eq!(cal.apply_at([1.7, 0.6, 3.0], 400.0), cal.apply_at([1.7, 0.6, 3.0], hottest));
    assert_ne!(cal.apply_at([1.7, 0.6, 3.0], 400.0), cal.apply_at([1.7, 0.6, 3.0], hottest - 1.0));
}

#[test]
fn apply_gyro_removes_the_temperature_dependent_bias_then_applies_g() {
    let mut cal = Calibration {
        gyro: GyroCalibration {
            matrix: [[1.0, 0.0, 0.0], [0.0, 2.0, 0.0], [0.5, 0.0, 1.0]],
            bias_dps: [1.0, -1.0, 0.0],
        },
        ..Calibration::identity(AccelRange::G2)
    };
    // w - b = (1, 2, 3); G (w - b) = (1, 4, 3.5).
    assert_eq!(cal.apply_gyro([2.0, 1.0, 3.0], 40.0), [1.0, 4.0, 3.5]);
    cal.temperature = Some(TemperatureModel {
        gyro_bias_dps: [[0.1, 0.0, 0.0], [0.0; 3], [0.0, 0.001, 0.0]],
        ..TemperatureModel::flat(30.0)
    });
    // dT = 10: b = (1 + 1, -1 + 1, 0); w - b = (0, 1, 3); G (w - b) = (0, 2, 3).
    assert!(close(cal.apply_gyro([2.0, 1.0, 3.0], 40.0), [0.0, 2.0, 3.0], 1e-6));
}

#[test]
fn plausible_calibration_is_accepted() {
    assert_eq!(plausible().validate(), Ok(()));
    assert_eq!(Calibration::identity(AccelRange::G4).validate(), Ok(()));
}

#[test]
fn non_finite_values_are_refused_wherever_they_are() {
    let mut cal = plausible();
    cal.offset_g[1] = f32::NAN;
    assert_eq!(cal.validate(), Err(CalibrationError::NonFinite));
    let mut cal = plausible();
    cal.matrix[2][0] = f32::INFINITY;
    assert_eq!(cal.validate(), Err(CalibrationError::NonFinite));
    let mut cal = plausible();
    cal.gyro.matrix[1][2] = f32::NAN;
    assert_eq!(cal.validate(), Err(CalibrationError::NonFinite));
    let mut cal = plausible();
    cal.temperature.as_mut().unwrap().scale[2][1] = f32::NAN;
    assert_eq!(cal.validate(), Err(CalibrationError::NonFinite));
}

#[test]
fn singular_matrices_are_refused() {
    let mut cal = plausible();
    cal.matrix = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 0.0]];
    assert!(matches!(cal.validate(), Err(CalibrationError::Singular { .. })));
    let mut cal = plausible();
    cal.gyro.matrix = [[1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]];
    assert!(matches!(cal.validate(), Err(CalibrationError::GyroSingular { .. })));
}

#[test]
fn absurd_scale_cross_axis_offset_and_bias_are_refused_with_the_axis() {
    let mut cal = plausible();
    cal.matrix[1][1] = 3.0;
    assert_eq!(cal.validate(), Err(CalibrationError::ScaleOutOfRange { axis: 1, value: 3.0 }));
    let mut cal = plausible();
    cal.matrix[0][2] = 0.4;
    assert_eq!(cal.validate(), Err(CalibrationError::CrossAxisOutOfRange { row: 0, col: 2, value: 0.4 }));
    let mut cal = plausible();
    cal.offset_g[2] = -0.9;
    assert_eq!(cal.validate(), Err(CalibrationError::OffsetOutOfRange { axis: 2, value_g: -0.9 }));
    let mut cal = plausible();
    cal.gyro.bias_dps[0] = 60.0;
    assert_eq!(cal.validate(), Err(CalibrationError::GyroBiasOutOfRange { axis: 0, value_dps: 60.0 }));
}

#[test]
fn an_absurd_gyro_matrix_is_refused_with_its_element() {
    let mut cal = plausible();
    cal.gyro.matrix[2][2] = 57.3; // rad/s taken for deg/s
    assert_eq!(cal.validate(), Err(CalibrationError::GyroScaleOutOfRange { axis: 2, value: 57.3 }));
    let mut cal = plausible();
    cal.gyro.matrix[1][0] = -0.3;
    assert_eq!(cal.validate(), Err(CalibrationError::GyroCrossAxisOutOfRange { row: 1, col: 0, value: -0.3 }));
}

#[test]
fn a_temperature_model_is_refused_when_it_leaves_the_limits_in_the_operating_range() {
    let mut cal = plausible();
    cal.temperature.as_mut().unwrap().ref_temp_c = 150.0;
    assert_eq!(cal.validate(), Err(CalibrationError::ReferenceTemperatureOutOfRange { value_c: 150.0 }));
    // 0.01 g/degC^2 on y: 42 g at -40 degC, 65 degC from T_ref.
    let mut cal = plausible();
    cal.temperature.as_mut().unwrap().offset_g[1][1] = 0.01;
    assert!(
        matches!(cal.validate(), Err(CalibrationError::OffsetDriftOutOfRange { axis: 1, .. })),
        "{:?}",
        cal.validate()
    );
    // 1 %/degC on z: 0.6 at 85 degC, beyond the scale drift limit.
    let mut cal = plausible();
    cal.temperature.as_mut().unwrap().scale[0][2] = 0.01;
    assert!(
        matches!(cal.validate(), Err(CalibrationError::ScaleDriftOutOfRange { axis: 2, .. })),
        "{:?}",
        cal.validate()
    );
    let mut cal = plausible();
    cal.temperature.as_mut().unwrap().gyro_bias_dps[0][0] = 1.0;
    assert!(
        matches!(cal.validate(), Err(CalibrationError::GyroBiasDriftOutOfRange { axis: 0, .. })),
        "{:?}",
        cal.validate()
    );
}

#[test]
fn range_sensitivities_follow_the_datasheet() {
    for (range, lsb) in [(AccelRange::G2, 16384.0), (AccelRange::G16, 2048.0)] {
        assert_eq!(range.lsb_per_g(), lsb);
        assert_eq!(AccelRange::from_full_scale_g(range.full_scale_g()), Some(range));
    }
    assert_eq!(AccelRange::from_full_scale_g(3), None);
}

#[test]
fn gyro_range_sensitivities_follow_the_datasheet_and_fs_sel_selects_each() {
    // NOTE: MPU-6000/6050 Product Specification rev 3.4, section 6.1: FS_SEL 0-3 are +-250, 500, 1000
    // and 2000 deg/s at 131, 65.5, 32.8 and 16.4 LSB per deg/s.
    let table = [(0, 250, 131.0), (1, 500, 65.5), (2, 1000, 32.8), (3, 2000, 16.4)];
    for (fs_sel, full_scale_dps, lsb) in table {
        let range = GyroRange::from_fs_sel(fs_sel);
        assert_eq!((range.fs_sel(), range.full_scale_dps(), range.lsb_per_dps()), (fs_sel, full_scale_dps, lsb));
        // GYRO_CONFIG holds FS_SEL in bits 4:3; the bits around it select nothing.
        assert_eq!(GyroRange::from_fs_sel(fs_sel | 0b1111_1100), range);
    }
    // The chip's f32 is the nearest f32 to the printed figure.
    assert_eq!(GyroRange::Dps1000.lsb_per_dps() as f32, 32.8f32);
    assert_eq!(STANDARD_GRAVITY, 9.80665, "CGPM 1901");
}
