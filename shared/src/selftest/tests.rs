use super::*;

/// SELF_TEST_X/Y/Z/A (0x0D-0x10) holding `accel` and `gyro` codes as RM-MPU-6000A 4.1 lays them out,
/// with every bit no code uses (the reserved bits 7:6 of SELF_TEST_A) set, so an unmasked read shows.
fn mpu6050_registers(accel: [u8; 3], gyro: [u8; 3]) -> [u8; 4] {
    let xyz = |i: usize| ((accel[i] >> 2) << 5) | gyro[i];
    let a = 0b1100_0000 | ((accel[0] & 3) << 4) | ((accel[1] & 3) << 2) | (accel[2] & 3);
    [xyz(0), xyz(1), xyz(2), a]
}

#[test]
fn mpu6050_codes_are_extracted_for_all_32_codes_of_every_axis() {
    for axis in 0..6 {
        for code in 0..32u8 {
            // The other axes hold 31 (all ones) so that a bit leaking across shows.
            let mut codes = [31u8; 6];
            codes[axis] = code;
            let registers = mpu6050_registers([codes[0], codes[1], codes[2]], [codes[3], codes[4], codes[5]]);
            assert_eq!(mpu6050_codes(registers), codes, "axis {axis} code {code}");
        }
    }
}

#[test]
fn mpu6050_factory_trim_follows_the_register_map_formulas() {
    // Code 1: 0.34 g at 4096 LSB/g; code 31: 0.92 g. Gyro code 1: 25 deg/s at 131 LSB per deg/s, y negative.
    let ft = |axis, code| factory_trim_lsb(Family::Mpu6050, axis, code).unwrap();
    assert!((ft(0, 1) - 0.34 * 4096.0).abs() < 0.01);
    assert!((ft(2, 31) - 0.92 * 4096.0).abs() < 0.05);
    assert!((ft(3, 1) - 25.0 * 131.0).abs() < 0.01);
    assert!((ft(4, 1) + 25.0 * 131.0).abs() < 0.01);
    assert!((ft(5, 11) - 25.0 * 131.0 * 1.046f32.powi(10)).abs() < 0.5);
    assert_eq!(factory_trim_lsb(Family::Mpu6050, 0, 0), None);
}

#[test]
fn mpu6500_factory_trim_is_2620_lsb_times_1_01_per_code() {
    let ft = |code| factory_trim_lsb(Family::Mpu6500, 0, code).unwrap();
    assert!((ft(1) - 2620.0).abs() < 0.01);
    assert!((ft(101) - 2620.0 * 1.01f32.powi(100)).abs() < 0.5);
    assert_eq!(mpu6500_codes([1, 2, 3], [4, 5, 6]), [1, 2, 3, 4, 5, 6]);
}

/// A raw result whose response on each axis is its factory trim times `scale`.
fn raw_with(family: Family, codes: [u8; 6], scale: [f32; 6]) -> SelfTestRaw {
    let off_lsb = [100.0, -50.0, 4000.0, 12.0, -8.0, 3.0];
    let on_lsb = core::array::from_fn(|i| off_lsb[i] + factory_trim_lsb(family, i, codes[i]).unwrap_or(0.0) * scale[i]);
    SelfTestRaw { family, codes, off_lsb, on_lsb, attempts: 1 }
}

#[test]
fn a_response_20_percent_off_fails_the_mpu6050_band_and_a_healthy_one_passes() {
    let codes = [14, 15, 16, 12, 13, 14];
    let healthy = evaluate(&raw_with(Family::Mpu6050, codes, [1.05, 0.97, 1.0, 1.1, 0.9, 1.0]));
    assert!(passed(&healthy), "{healthy:?}");
    let off = evaluate(&raw_with(Family::Mpu6050, codes, [1.0, 1.0, 1.0, 1.0, 1.2, 1.0]));
    assert!(!passed(&off));
    assert!(!off[4].passed && off.iter().filter(|v| v.passed).count() == 5);
    assert!((off[4].deviation_percent.unwrap() - 20.0).abs() < 0.01, "{:?}", off[4]);
    assert!(off[4].response < 0.0, "the y gyro's response is negative");
}

#[test]
fn the_mpu6500_datasheet_band_is_the_application_notes_plus_minus_50_percent() {
    let codes = [120, 130, 140, 100, 110, 90];
    let within = evaluate(&raw_with(Family::Mpu6500, codes, [1.45, 0.55, 1.0, 0.55, 3.0, 1.0]));
    assert!(datasheet_passed(&within), "{within:?}");
    let outside = evaluate(&raw_with(Family::Mpu6500, codes, [1.55, 1.0, 1.0, 0.45, 1.0, 1.0]));
    assert_eq!(outside.map(|v| v.datasheet_passed), [false, true, true, false, true, true]);
}

#[test]
fn a_20_percent_off_axis_fails_accelcals_band_on_the_mpu6500_family_though_its_datasheet_passes_it() {
    let codes = [120, 130, 140, 100, 110, 90];
    let off = evaluate(&raw_with(Family::Mpu6500, codes, [1.2, 1.0, 1.0, 1.0, 1.0, 0.8]));
    assert_eq!(off.map(|v| v.passed), [false, true, true, true, true, false]);
    assert!(datasheet_passed(&off) && !passed(&off), "{off:?}");
    let edge = evaluate(&raw_with(Family::Mpu6500, codes, [1.139, 0.861, 1.0, 1.0, 1.0, 1.0]));
    assert!(passed(&edge), "{edge:?}");
}

#[test]
fn a_code_of_zero_is_judged_by_the_absolute_window() {
    let mut raw = raw_with(Family::Mpu6500, [0, 1, 1, 0, 1, 1], [1.0; 6]);
    raw.on_lsb[0] = raw.off_lsb[0] + 0.5 * 16384.0; // 0.5 g: inside 225-675 mg
    raw.on_lsb[3] = raw.off_lsb[3] + 40.0 * 131.0; // 40 deg/s: below 60
    let verdicts = evaluate(&raw);
    assert_eq!((verdicts[0].factory_trim, verdicts[0].passed), (None, true));
    assert_eq!((verdicts[3].deviation_percent, verdicts[3].passed), (None, false));
    assert!((verdicts[0].response - 0.5).abs() < 1e-4);
}

#[test]
fn a_baseline_shift_of_more_than_10_mg_or_1_dps_is_a_move() {
    let before = [0.0; 6];
    let lsb_per_g = AccelRange::G8.lsb_per_g();
    assert!(!baseline_moved(Family::Mpu6050, &before, &[0.009 * lsb_per_g, 0.0, 0.0, 0.9 * 131.0, 0.0, 0.0]));
    assert!(baseline_moved(Family::Mpu6050, &before, &[0.0, 0.011 * lsb_per_g, 0.0, 0.0, 0.0, 0.0]));
    assert!(baseline_moved(Family::Mpu6050, &before, &[0.0, 0.0, 0.0, 0.0, 0.0, -1.1 * 131.0]));
}

#[test]
fn the_largest_stored_self_test_fits_its_record_and_reads_back_as_it_was() {
    let raw = SelfTestRaw {
        family: Family::Mpu6500,
        codes: [u8::MAX; 6],
        off_lsb: [f32::MIN; 6],
        on_lsb: [-0.0, f32::MAX, 1.5, f32::EPSILON, 2620.0, -3275.5],
        attempts: u8::MAX,
    };
    let stored = StoredSelfTest { unix_time_s: u32::MAX, raw };
    let record = stored.record();
    assert_eq!(record.len(), 61, "a 5-byte time and 56 bytes of raw");
    assert_eq!(StoredSelfTest::from_record(&record), Some(stored));
    assert_eq!(StoredSelfTest::from_record(&record[..60]), None, "a cut record is refused");
}
