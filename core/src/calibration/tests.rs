use super::*;

#[test]
fn a_device_calibration_survives_its_json_form_bit_for_bit() {
    let mut calibration = Calibration::identity(AccelRange::G4);
    calibration.matrix[0][1] = 0.0023;
    calibration.offset_g = [0.012, -0.034, 0.056];
    calibration.mean_temp_c = 27.5;
    calibration.filter = LowPassFilter::Hz10;
    let json = CalibrationJson::from_device(&calibration);
    assert_eq!(json.matrix[0][1], f64::from(0.0023f32));
    let text = serde_json::to_string(&json).unwrap();
    assert_eq!(CalibrationJson::from_text(&text).unwrap().to_device(AccelRange::G2).unwrap(), calibration);
}

#[test]
fn the_description_names_the_temperature_model_when_there_is_one() {
    let mut calibration = Calibration::identity(AccelRange::G2);
    assert!(!describe(&calibration).contains("temperature"));
    let mut model = TemperatureModel::flat(25.0);
    model.offset_g[0] = [0.75e-3, -0.7e-3, 1.4e-3];
    calibration.temperature = Some(model);
    let text = describe(&calibration);
    assert!(text.ends_with("; temperature model around 25.0 degC (offset +0.75 -0.70 +1.40 mg/degC)"), "{text}");
}

#[test]
fn an_offset_that_rounds_to_zero_is_described_without_a_minus() {
    let calibration =
        Calibration { offset_g: [-0.000_004, 0.012_34, -0.000_001], ..Calibration::identity(AccelRange::G2) };
    let line = describe(&calibration);
    assert!(line.contains("offset +0.00 +12.34 +0.00 mg"), "{line}");
}

#[test]
fn the_description_names_the_gyro_matrix_only_when_it_was_fitted() {
    let mut calibration = Calibration::identity(AccelRange::G2);
    calibration.gyro.bias_dps = [-1.2, 0.8, 0.35];
    assert!(describe(&calibration).ends_with("; gyro bias -1.200 +0.800 +0.350 deg/s"), "{}", describe(&calibration));
    calibration.gyro.matrix[1][1] = 1.0163;
    let line = describe(&calibration);
    assert!(line.ends_with("; gyro G 1.00000 1.01630 1.00000, bias -1.200 +0.800 +0.350 deg/s"), "{line}");
}
