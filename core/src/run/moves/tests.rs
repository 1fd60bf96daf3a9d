use super::*;

/// A sample at rest (1 g on z) with the gyro reading `rate_dps` on x.
fn sample(index: u32, rate_dps: f32) -> Sample {
    Sample {
        index,
        time_us: u64::from(index) * 10_000,
        accel_g: [0.0, 0.0, 1.0],
        gyro_dps: [rate_dps, 0.0, 0.0],
        temp_c: 25.0,
    }
}

/// Feeds `rates` to a watch that needs `still` samples at rest; returns it and how many it took.
fn watched(rates: &[f32], still: usize) -> (Watch, usize) {
    let mut watch = Watch::new([0.0; 3], still);
    let taken = rates.iter().enumerate().take_while(|(i, r)| watch.push(&sample(*i as u32, **r))).count();
    (watch, taken)
}

/// A turn: `before` samples at rest, then `turning` at `rate` deg/s, then `after` at rest.
fn turn(before: usize, turning: usize, rate: f32, after: usize) -> Vec<f32> {
    [vec![0.0; before], vec![rate; turning], vec![0.0; after]].concat()
}

#[test]
fn a_move_ends_after_the_turn_and_the_rest_that_follows_it() {
    let (watch, taken) = watched(&turn(5, 20, 90.0, 200), 50);
    // 5 at rest, 20 turning, then the 50th still sample ends it (the push that ends returns false).
    assert_eq!(taken, 5 + 20 + 49);
    let recording = watch.finish(0, "+X").unwrap();
    assert_eq!(recording.samples.len(), 75);
    assert_eq!(recording.end_mean_g, [0.0, 0.0, 1.0]);
}

#[test]
fn a_clipped_or_gapped_or_unfinished_move_is_named_and_not_recorded() {
    let limit = f32::from(GYRO_RANGE.full_scale_dps()) * 0.996;
    let (watch, _) = watched(&turn(5, 20, limit, 200), 50);
    let clipped = watch.finish(0, "+X").unwrap_err();
    assert_eq!(clipped, Problem::Clipped(20));
    assert!(clipped.to_string().contains("turn more slowly"), "{clipped}");
    let (watch, _) = watched(&turn(5, 20, 0.99 * limit, 200), 50);
    assert!(watch.finish(0, "+X").is_ok(), "just below the range is not clipped");
    let (watch, _) = watched(&turn(5, 20, 90.0, 200), 50);
    assert_eq!(watch.finish(3, "+X").unwrap_err(), Problem::Lost(3));
    let (watch, _) = watched(&turn(5, 20, 90.0, 10), 50);
    assert_eq!(watch.finish(0, "+X").unwrap_err(), Problem::NeverStill);
    let (watch, taken) = watched(&turn(0, 20, 90.0, 100), 50);
    assert_eq!((watch.finish(0, "+X").unwrap_err(), taken), (Problem::AlreadyMoving, 0));
}

#[test]
fn a_board_put_down_elsewhere_without_a_turn_ends_the_move_which_is_dropped() {
    let mut watch = Watch::new([0.0; 3], 50);
    let tilted = |index: u32, deg: f64| Sample {
        accel_g: [deg.to_radians().sin() as f32, 0.0, deg.to_radians().cos() as f32],
        ..sample(index, 0.0)
    };
    // 4.9 degrees from where it began does not start it; 6 degrees does, and 50 still samples
    // there end it.
    assert!((0..10).all(|i| watch.push(&tilted(i, 0.0))));
    assert!((10..100).all(|i| watch.push(&tilted(i, 4.9))));
    let taken = (100..300).take_while(|&i| watch.push(&tilted(i, 6.0))).count();
    assert_eq!(taken, 49);
    assert_eq!(watch.finish(0, "+X").unwrap_err(), Problem::NoTurnSeen);
}

#[test]
fn a_board_put_down_elsewhere_before_the_recording_began_ends_the_move_too() {
    let mut watch = Watch::new([0.0; 3], 50);
    watch.rest_g = Some([0.0, 0.0, 1.0]);
    let elsewhere = |index: u32| Sample { accel_g: [1.0, 0.0, 0.0], ..sample(index, 0.0) };
    let taken = (0..300).take_while(|&i| watch.push(&elsewhere(i))).count();
    assert_eq!(taken, 49, "the rest elsewhere ends it after 50 samples, not at the 30 s limit");
    assert_eq!(watch.finish(0, "+X").unwrap_err(), Problem::NoTurnSeen);
}

#[test]
fn a_move_that_came_to_rest_at_the_target_ends_the_wait_for_it_and_no_other_does() {
    let faces = crate::orientation::faces();
    let (plus_z, plus_x) =
        (faces.iter().find(|f| f.name == "+Z").unwrap(), faces.iter().find(|f| f.name == "+X").unwrap());
    let mut moves = Moves::at(100);
    assert!(!moves.rests_at(plus_z, 0.5), "no move recorded yet");
    let (watch, _) = watched(&turn(5, 20, 90.0, 200), 50);
    moves.pending = Some((0, watch.finish(0, "+Z").unwrap()));
    // The recording ended at rest with 1 g on z: at +Z, for the half second a goal's capture needs.
    assert!(moves.rests_at(plus_z, 0.5));
    assert!(!moves.rests_at(plus_x, 0.5), "at rest, but at another position");
    assert!(!moves.rests_at(plus_z, 2.0), "a rest shorter than the settle asked for");
}

#[test]
fn a_move_that_came_to_rest_just_outside_the_target_s_tolerance_does_not_end_the_wait() {
    let faces = crate::orientation::faces();
    let plus_z = faces.iter().find(|f| f.name == "+Z").unwrap();
    let mut moves = Moves::at(100);
    // Tilted about y by the tolerance and 1 degree more, or 1 degree less: the edge is the target's own.
    let tilted = |deg: f64| [deg.to_radians().sin(), 0.0, deg.to_radians().cos()];
    let rest_at = |moves: &mut Moves, deg: f64| {
        let (watch, _) = watched(&turn(5, 20, 90.0, 200), 50);
        let recording = Recording { end_mean_g: tilted(deg), ..watch.finish(0, "+Z").unwrap() };
        moves.pending = Some((0, recording));
        moves.rests_at(plus_z, 0.5)
    };
    assert!(rest_at(&mut moves, plus_z.tolerance_deg - 1.0), "inside the tolerance");
    assert!(!rest_at(&mut moves, plus_z.tolerance_deg + 1.0), "outside it: the wait must still judge the board");
}
