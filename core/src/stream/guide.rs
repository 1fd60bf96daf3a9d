//! Which way to turn a board whose stream is being calibrated: the six faces and eight corners,
//! each visited once a still period rests within [`VISITED_DEG`] of it, the next one the nearest
//! not yet visited, in whatever order the person chooses; then fresh orientations (the twelve
//! edges), to verify the calibration where it was not trained. A still period near a face or corner
//! trains the calibration; one away from them all is fresh and verifies it.

use crate::limits::VISITED_DEG;
use shared::linalg::{dot, norm, scale};

/// A target: its name (the axes that point up) and its direction.
fn targets() -> Vec<(String, [f64; 3])> {
    let sign = |s: f64| if s > 0.0 { "+" } else { "-" };
    let faces = (0..6).map(|k| {
        let mut up = [0.0; 3];
        up[k % 3] = if k < 3 { 1.0 } else { -1.0 };
        (format!("{}{}", sign(up[k % 3]), ["X", "Y", "Z"][k % 3]), up)
    });
    let corners = (0..8).map(|k| {
        let up = [k & 1, k & 2, k & 4].map(|b| if b == 0 { 1.0 } else { -1.0 });
        (format!("{}X{}Y{}Z", sign(up[0]), sign(up[1]), sign(up[2])), scale(up, 1.0 / 3f64.sqrt()))
    });
    faces.chain(corners).collect()
}

/// The twelve edges: two axes up at 45 degrees, each more than [`VISITED_DEG`] from every face
/// and corner (45 and 35 degrees).
fn edges() -> Vec<(String, [f64; 3])> {
    let sign = |s: f64| if s > 0.0 { "+" } else { "-" };
    let mut edges = Vec::new();
    for (i, j) in [(0, 1), (0, 2), (1, 2)] {
        for (si, sj) in [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)] {
            let mut up = [0.0; 3];
            (up[i], up[j]) = (si / 2f64.sqrt(), sj / 2f64.sqrt());
            let name = format!("{}{}{}{}", sign(si), ["X", "Y", "Z"][i], sign(sj), ["X", "Y", "Z"][j]);
            edges.push((name, up));
        }
    }
    edges
}

/// Whether a still period resting with `up` up trains the calibration (within [`VISITED_DEG`] of
/// a face or corner) rather than verifying it.
pub fn trains(up: [f64; 3]) -> bool {
    targets().iter().any(|(_, t)| angle_deg(up, *t) <= VISITED_DEG)
}

/// The face, corner or edge nearest to `up`, by name ("+X", "+X-Y+Z", "+X+Z").
pub fn nearest_name(up: [f64; 3]) -> String {
    let all = targets().into_iter().chain(edges());
    all.min_by(|a, b| angle_deg(up, a.1).total_cmp(&angle_deg(up, b.1))).map(|(name, _)| name).unwrap_or_default()
}

/// Whether every face and corner has been rested at.
pub fn all_rested(rested: &[[f64; 3]]) -> bool {
    targets().iter().all(|(_, t)| rested.iter().any(|r| angle_deg(*r, *t) <= VISITED_DEG))
}

/// The advice once every face and corner is rested: the nearest edge not yet rested at.
fn fresh_turn(up: [f64; 3], rested: &[[f64; 3]]) -> String {
    let open: Vec<(String, [f64; 3])> =
        edges().into_iter().filter(|(_, e)| rested.iter().all(|r| angle_deg(*r, *e) > VISITED_DEG)).collect();
    match open.iter().min_by(|a, b| angle_deg(up, a.1).total_cmp(&angle_deg(up, b.1))) {
        Some((name, edge)) => format!(
            "verify: turn to a fresh orientation, {name} up ({:.0} deg away), and hold it still",
            angle_deg(up, *edge)
        ),
        None => "every face, corner and edge rested: Ctrl-C to finish".to_owned(),
    }
}

fn angle_deg(a: [f64; 3], b: [f64; 3]) -> f64 {
    (dot(a, b) / (norm(a) * norm(b))).clamp(-1.0, 1.0).acos().to_degrees()
}

/// The advice for a person holding the board with `up` up, having rested at `rested` (means in g).
pub fn next_turn(up: [f64; 3], rested: &[[f64; 3]]) -> String {
    let open: Vec<(String, [f64; 3])> =
        targets().into_iter().filter(|(_, t)| rested.iter().all(|r| angle_deg(*r, *t) > VISITED_DEG)).collect();
    let nearest = open.iter().min_by(|a, b| angle_deg(up, a.1).total_cmp(&angle_deg(up, b.1)));
    match nearest {
        Some((name, target)) => format!(
            "turn to {name} up ({:.0} deg away) and hold it still; {} of 14 orientations left",
            angle_deg(up, *target),
            open.len()
        ),
        None => fresh_turn(up, rested),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_next_turn_is_the_nearest_orientation_not_yet_rested_at() {
        assert!(
            next_turn([0.0, 0.0, 1.0], &[]).starts_with("turn to +Z up (0 deg away)"),
            "{}",
            next_turn([0.0, 0.0, 1.0], &[])
        );
        let advice = next_turn([0.0, 0.0, 1.0], &[[0.02, 0.0, 0.99]]);
        assert!(advice.contains("(55 deg away)") && advice.contains("13 of 14"), "{advice}");
    }

    #[test]
    fn faces_and_corners_train_and_once_all_are_rested_the_person_is_sent_to_a_fresh_edge() {
        let corner = [1.0, 1.0, 1.0].map(|v: f64| v / 3f64.sqrt());
        assert!(trains([0.02, 0.0, 1.0]) && trains(corner));
        assert!(!trains([1.0, 1.0, 0.0].map(|v: f64| v / 2f64.sqrt())), "an edge is 35 deg from the nearest corner");
        let all: Vec<[f64; 3]> = targets().into_iter().map(|(_, t)| t).collect();
        assert!(all_rested(&all) && !all_rested(&all[1..]));
        assert_eq!((nearest_name([0.1, 0.0, -0.99]), nearest_name([0.6, -0.6, 0.5])), ("-Z".into(), "+X-Y+Z".into()));
        let advice = next_turn([0.0, 0.0, 1.0], &all);
        assert!(advice.starts_with("verify: turn to a fresh orientation, +X+Z up (45 deg away)"), "{advice}");
    }
}
