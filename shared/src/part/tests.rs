use super::*;

#[test]
fn every_known_who_am_i_names_its_part_and_others_are_unknown() {
    let named = [(0x68, "MPU-6050"), (0x70, "MPU-6500"), (0x71, "MPU-9250"), (0x73, "MPU-9255"), (0x98, "ICM-20689")];
    for (who_am_i, name) in named {
        assert_eq!(Part::from_who_am_i(who_am_i).name(), name, "0x{who_am_i:02x}");
    }
    for who_am_i in [0x72, 0x74, 0x00, 0xFF] {
        assert_eq!(Part::from_who_am_i(who_am_i), Part::Unknown(who_am_i));
        assert_eq!(Part::from_who_am_i(who_am_i).claimed_family(), None);
    }
}

#[test]
fn a_6500_family_map_answering_0x68_contradicts_its_who_am_i() {
    let behaves_6500 = Behaviour { accel_config2_kept: true, offsets_at_0x77: true };
    let id = Identification { part: Part::from_who_am_i(0x68), family: behaves_6500.family().unwrap() };
    assert!(id.contradicts_who_am_i());
    let honest = Identification { part: Part::from_who_am_i(0x70), family: Family::Mpu6500 };
    assert!(!honest.contradicts_who_am_i());
    let unknown = Identification { part: Part::from_who_am_i(0x72), family: Family::Mpu6500 };
    assert!(!unknown.contradicts_who_am_i(), "an unknown part claims no family");
}

#[test]
fn mixed_register_evidence_names_no_family() {
    assert_eq!(Behaviour { accel_config2_kept: true, offsets_at_0x77: false }.family(), None);
    assert_eq!(Behaviour { accel_config2_kept: false, offsets_at_0x77: false }.family(), Some(Family::Mpu6050));
}

#[test]
fn temperature_formulas_follow_the_datasheets() {
    // MPU-6050: 0 LSB is 36.53 degC; MPU-6500: 0 LSB is 21 degC, 333.87 LSB per degC; ICM-20689: 25 degC, 326.8.
    assert!((TemperatureFormula::MPU6050.celsius(-3580) - (36.53 - 3580.0 / 340.0)).abs() < 1e-4);
    assert!((Part::Mpu9250.temperature(Family::Mpu6500).celsius(3339) - 31.0).abs() < 0.01);
    assert!((Part::Icm20689.temperature(Family::Mpu6500).celsius(-1634) - 20.0).abs() < 0.01);
    assert_eq!(Part::Unknown(0x72).temperature(Family::Mpu6500), TemperatureFormula::MPU6500);
    assert_eq!(Part::Unknown(0x72).temperature(Family::Mpu6050), TemperatureFormula::MPU6050);
    for formula in [TemperatureFormula::MPU6050, TemperatureFormula::MPU6500, TemperatureFormula::ICM20600] {
        assert!((formula.celsius(formula.raw(27.3)) - 27.3).abs() < 0.5 / formula.lsb_per_c + 1e-4);
    }
}

#[test]
fn an_offset_pair_is_a_15_bit_value_in_steps_of_1_1024_g_with_bit_0_reserved() {
    // NOTE: RM-MPU-9250A 4.39: XA_OFFS[14:7] in the high byte, XA_OFFS[6:0] in bits 7:1 of the low.
    let cases = [
        ([0x00, 0x01], 0.0),
        ([0x00, 0x02], 1.0 / 1024.0),
        ([0x01, 0x00], 0.125),
        ([0xFF, 0xFE], -1.0 / 1024.0),
        ([0xFF, 0xFF], -1.0 / 1024.0),
        ([0x7F, 0xFE], 16.0 - 1.0 / 1024.0),
        ([0x80, 0x00], -16.0),
    ];
    for ([high, low], g) in cases {
        assert_eq!(accel_offset_g(high, low), g, "0x{high:02x}{low:02x}");
    }
    assert_eq!(Family::Mpu6050.accel_offset_registers(), [0x06, 0x08, 0x0A]);
    assert_eq!(Family::Mpu6500.accel_offset_registers(), [0x77, 0x7A, 0x7D]);
}
