//! Which gyro axes the turns exercise: a turn about the vertical leaves gravity where it was, so it
//! says nothing about the gyro; only the part of each axis' turning about a horizontal line counts.

use nalgebra::{UnitQuaternion, Vector3};
use shared::linalg::Vec3;

use super::integrate::Turn;
use crate::limits::MIN_INFORMATIVE_TURN_DEG;

/// Per raw gyro axis, the degrees it turned while lying horizontal (weighted by how horizontal).
pub fn informative_turn_deg(turns: &[Turn]) -> Vec3<f64> {
    turns.iter().map(informative_of).fold([0.0; 3], |a, b| [a[0] + b[0], a[1] + b[1], a[2] + b[2]])
}

fn informative_of(turn: &Turn) -> Vec3<f64> {
    let mut q = UnitQuaternion::identity();
    let mut total = [0.0; 3];
    for i in 0..turn.rates_dps.len() {
        let step = turn.rate_rad(i) * turn.interval_s;
        let up = q.inverse_transform_vector(&Vector3::from(turn.up_before));
        for (k, sum) in total.iter_mut().enumerate() {
            let horizontal = (1.0 - up[k] * up[k]).max(0.0).sqrt();
            *sum += step[k].abs().to_degrees() * horizontal;
        }
        q *= UnitQuaternion::from_scaled_axis(step);
    }
    total
}

/// The axes below [`MIN_INFORMATIVE_TURN_DEG`].
pub(super) fn missing_axes(turned_deg: &Vec3<f64>) -> Vec<usize> {
    (0..3).filter(|&k| turned_deg[k] < MIN_INFORMATIVE_TURN_DEG).collect()
}

/// What to tell the user about axes that did not turn enough: which, and how to turn them.
pub(super) fn advice(axes: &[usize], turned_deg: &Vec3<f64>) -> String {
    let how: Vec<String> = axes.iter().map(|&k| how_to_turn(k, turned_deg[k])).collect();
    format!("the gyro's scale cannot be fitted: turns about the vertical carry no information; {}", how.join("; "))
}

/// The instruction for one axis: roll the board over the edge parallel to it.
fn how_to_turn(axis: usize, turned_deg: f64) -> String {
    let name = ["X", "Y", "Z"][axis];
    let [a, b] = [["Y", "Z"], ["Z", "X"], ["X", "Y"]][axis];
    format!(
        "the {name} axis turned only {turned_deg:.0} degrees about a horizontal line (needs {MIN_INFORMATIVE_TURN_DEG:.0}): \
         add turns about the board's {name} axis, rolling it over an edge parallel to {name}, e.g. from +{a} up to +{b} up and on to -{a} up"
    )
}
