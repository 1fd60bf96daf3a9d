//! The chip's 9-parameter fit on request: from captures a hand placed a few degrees off, never made
//! active, and refused by name when the captures cannot determine it.

use shared::linalg;
use shared::ortho9::Ortho9Error;
use shared::protocol::{DeviceError, Request, Response, MAX_KEPT_CAPTURES};

use super::tests::{ask, boot, run, Flash, SimDevice};
use crate::sim::SimMpu6050;

/// The quick calibration's ten orientations (the six faces and four corners of a tetrahedron), each
/// tilted about 4 degrees as a hand would leave it.
fn tilted_quick_set() -> [[f32; 3]; 10] {
    let c = 0.577_350_26;
    let set = [
        [c, c, c],
        [-c, -c, c],
        [-1.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 0.0, -1.0],
        [0.0, 0.0, 1.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [-c, c, -c],
        [c, -c, -c],
    ];
    // NOTE: 0.07 rad = 4 degrees, a different direction for each.
    set.map(|up| {
        let tilted = linalg::add(up, [0.07 * up[1], 0.07 * up[2], 0.07 * up[0]]);
        linalg::scale(tilted, 1.0 / linalg::norm(tilted))
    })
}

fn capture(device: &mut SimDevice, up: [f32; 3]) {
    device.bus_mut().place(up);
    let (answer, _) = run(device, 7, Request::Capture { seconds: 5 });
    assert!(matches!(answer, Response::Captured { .. }), "{answer:?}");
}

#[test]
fn the_chip_s_ortho9_fit_of_ten_tilted_captures_recovers_the_true_model_and_is_not_made_active() {
    // NOTE: a sub-mg claim about the fit needs one temperature: the settled static sensor.
    let mut device = boot(SimMpu6050::settled(3), Flash::new());
    let truth = device.bus_mut().physics.truth;
    let before = device.active_calibration();
    tilted_quick_set().into_iter().for_each(|up| capture(&mut device, up));
    let Response::Ortho9Fitted { calibration, captures, iterations } = ask(&mut device, 8, Request::FitOrtho9) else {
        panic!("no fit")
    };
    assert_eq!(captures, 10);
    // Noise of 5 s means is 0.13 mg per axis (400 ug/sqrt(Hz)); ten captures carry the offsets to
    // within a few tenths of a mg and M to a few 1e-4.
    for axis in 0..3 {
        let offset_error_mg = (calibration.offset_g[axis] - truth.offset_g[axis]).abs() * 1000.0;
        assert!(offset_error_mg < 0.5, "offset {axis} off by {offset_error_mg} mg");
    }
    let matrix_error = linalg::max_abs_diff(&calibration.matrix, &truth.matrix);
    assert!(matrix_error < 1e-3, "M off by {matrix_error}");
    // One residual degree of freedom: the RMS of |a| - 1 g is of the order of the noise.
    assert!(calibration.residual_mg > 0.0 && calibration.residual_mg < 0.3, "{}", calibration.residual_mg);
    assert_eq!(calibration.origin, shared::calibration::Origin::CHIP_ORTHO9);
    println!(
        "on-chip ortho9, 10 tilted 5 s captures: |dM| max {matrix_error:.2e}, {iterations} iterations, {calibration:?}"
    );
    assert_eq!(device.active_calibration(), before);
}

#[test]
fn too_few_captures_are_refused_by_count_and_clear_positions_forgets_them() {
    let mut device = boot(SimMpu6050::new(4), Flash::new());
    tilted_quick_set()[..8].iter().for_each(|&up| capture(&mut device, up));
    let answer = ask(&mut device, 3, Request::FitOrtho9);
    assert_eq!(answer, Response::Error(DeviceError::Ortho9(Ortho9Error::TooFewReadings(8))));
    ask(&mut device, 4, Request::ClearPositions);
    let answer = ask(&mut device, 5, Request::FitOrtho9);
    assert_eq!(answer, Response::Error(DeviceError::Ortho9(Ortho9Error::TooFewReadings(0))));
}

#[test]
fn captures_all_at_one_orientation_are_refused_as_ill_conditioned() {
    let mut device = boot(SimMpu6050::new(5), Flash::new());
    (0..9).for_each(|_| capture(&mut device, [0.0, 0.0, 1.0]));
    let answer = ask(&mut device, 3, Request::FitOrtho9);
    assert!(matches!(answer, Response::Error(DeviceError::Ortho9(Ortho9Error::IllConditioned(_)))), "{answer:?}");
}

#[test]
fn the_chip_keeps_the_latest_sixteen_captures() {
    let mut device = boot(SimMpu6050::new(6), Flash::new());
    let set = tilted_quick_set();
    let all: Vec<[f32; 3]> = set.iter().chain(set.iter()).copied().take(MAX_KEPT_CAPTURES + 1).collect();
    all.iter().for_each(|&up| capture(&mut device, up));
    let Response::Ortho9Fitted { captures, .. } = ask(&mut device, 8, Request::FitOrtho9) else { panic!("no fit") };
    assert_eq!(usize::from(captures), MAX_KEPT_CAPTURES);
}
