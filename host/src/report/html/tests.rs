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
