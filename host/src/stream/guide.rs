//! Which way to turn a board whose stream is being calibrated: the six faces and eight corners,
//! each visited once a still period rests within [`VISITED_DEG`] of it, the next one the nearest
//! not yet visited, in whatever order the person chooses.

use shared::linalg::{dot, norm, scale};

/// A still period this close to a target, in degrees, has visited it.
pub const VISITED_DEG: f64 = 25.0;

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
        None => "every face and corner rested: rest it anywhere else, or Ctrl-C to finish".to_owned(),
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
}
