use super::*;

#[test]
fn a_position_s_components_are_shown_to_four_decimals_near_zero_too() {
    let position = PositionResult {
        name: "+Z".into(),
        raw_g: [0.0276, -3e-5, 0.9999],
        calibrated_g: [2.4e-5, -3.1e-5, 1.00002],
        residual_before_mg: 1.5,
        residual_after_mg: 0.02,
    };
    let mut row = String::new();
    position_row(&mut row, 0, &position);
    assert!(row.contains(">0.0276</span> <span"), "{row}");
    assert!(!row.contains("e-5<") && !row.contains(">-0.0000<"), "{row}");
    assert_eq!(row.matches(">0.0000</span>").count(), 3, "{row}");
    assert!(row.contains(">1.0000</span></td>"), "{row}");
}

#[test]
fn a_column_read_together_keeps_its_decimals_and_standard_errors_stay_scientific() {
    // A cross-axis term of 2.5e-4 beside a scale of 1.001: both to six decimals.
    let (small, near_one) = (fixed_cell("/m/0/1", Some(2.544355e-4), 6), fixed_cell("/m/0/0", Some(1.001101), 6));
    assert!(small.contains(">0.000254</span>") && near_one.contains(">1.001101</span>"), "{small} {near_one}");
    let (tiny, large) = (scientific_cell("/e/0", Some(2.633774e-4), 3), scientific_cell("/e/1", Some(0.0123), 3));
    assert!(tiny.contains(">2.63e-4</span>") && large.contains(">1.23e-2</span>"), "{tiny} {large}");
}
